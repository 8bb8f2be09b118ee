#!/usr/bin/env python3
"""A protocol-1 tracker for tests that finds nothing and says how many frames it has seen
since the last request with reset: true ("frames N"): a sequence's frames must count up."""
import json
import sys

hello = json.loads(sys.stdin.readline())
assert hello == {"protocol": 1, "tracker": sys.argv[1]}, hello
print(json.dumps({"protocol": 1, "ready": True}), flush=True)
frames_since_reset = 0
for line in sys.stdin:
    request = json.loads(line)
    frames_since_reset = 1 if request["reset"] else frames_since_reset + 1
    print(json.dumps({"status": "not_detected", "message": "frames %d" % frames_since_reset}),
          flush=True)
