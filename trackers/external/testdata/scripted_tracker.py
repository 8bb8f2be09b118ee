#!/usr/bin/env python3
"""A protocol-1 tracker for tests whose behaviour is the frame number modulo 10:
0 a pose made of the request, 1 SIGSEGV, 2 a hang, 3 a line that is not JSON, 4 a pose that
is not a rotation, 5 exit status 3, 6 not_detected, 7 a reply with a NaN, others a pose."""
import json
import math
import os
import signal
import sys
import time

hello = json.loads(sys.stdin.readline())
assert hello == {"protocol": 1, "tracker": sys.argv[1]}, hello
print(json.dumps({"protocol": 1, "ready": True}), flush=True)
frames_since_reset = 0
for line in sys.stdin:
    request = json.loads(line)
    behaviour = request["frame"] % 10
    if request["reset"]:
        frames_since_reset = 0
    frames_since_reset += 1
    if behaviour == 1:
        os.kill(os.getpid(), signal.SIGSEGV)
    if behaviour == 2:
        time.sleep(1000)
    if behaviour == 3:
        print("this is not JSON", flush=True)
        continue
    if behaviour == 5:
        sys.exit(3)
    if behaviour == 6:
        print(json.dumps({"status": "not_detected"}), flush=True)
        continue
    angle = 0.1 * request["frame"]
    rotation = [math.cos(angle), -math.sin(angle), 0, math.sin(angle), math.cos(angle), 0, 0, 0, 1]
    if behaviour == 4:
        rotation[0] = 2.0
    translation = [request["camera"]["fx"], request["width"], request["height"]]
    if behaviour == 7:
        translation[0] = float("nan")
    size = os.path.getsize(request["image"])
    reply = {
        "status": "ok",
        "poses": [{"R": rotation, "t": translation}],
        "message": "%s %s channels %d png %s frames %d" % (
            request["marker_kind"], os.path.basename(request["marker"]), request["channels"],
            "yes" if size > 0 else "no", frames_since_reset),
        "time_ms": 1.5,
    }
    print(json.dumps(reply), flush=True)
