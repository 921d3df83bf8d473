#!/usr/bin/python3
"""Queues one message with acommsd and prints its id.

    python3 submit.py --socket var/vehicle/acommsd.sock example.Status '{"depth": 10}'
    python3 submit.py --ttl 60 example.Status @status.json     (JSON from a file)
"""

import argparse
import json
import sys

from acomms_client import AcommsClient, AcommsError, default_socket


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--socket", default=default_socket(),
                        help="acommsd's unix socket (default: $ACOMMSD_SOCKET or %(default)s)")
    parser.add_argument("--ttl", type=float, default=0.0,
                        help="seconds the message may wait in the queue (default: the queue's)")
    parser.add_argument("type", help="DCCL type, e.g. example.Status")
    parser.add_argument("message", help="the message as JSON, or @FILE holding it")
    args = parser.parse_args()

    text = args.message
    if text.startswith("@"):
        with open(text[1:]) as f:
            text = f.read()
    try:
        message = json.loads(text)
    except json.JSONDecodeError as e:
        print(f"submit.py: the message is not JSON: {e}", file=sys.stderr)
        return 2

    try:
        with AcommsClient(args.socket) as acomms:
            message_id = acomms.submit(args.type, message, ttl=args.ttl)
    except AcommsError as e:
        print(f"submit.py: {e}", file=sys.stderr)
        return 1
    print(f"queued {args.type} as message {message_id}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
