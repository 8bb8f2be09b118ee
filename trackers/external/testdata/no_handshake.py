#!/usr/bin/env python3
"""A tracker for tests that answers the handshake with the wrong line."""
import sys

sys.stdin.readline()
print("hello?", flush=True)
sys.stdin.readline()
