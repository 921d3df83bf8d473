#!/usr/bin/python3
"""Prints the messages acommsd receives from the link, one line each, until
Ctrl-C (or --count messages, or --seconds).

    python3 subscribe.py --socket var/vehicle/acommsd.sock
    python3 subscribe.py --type example.Status --src 2 --json
"""

import argparse
import json
import signal
import sys
import threading
import time

from acomms_client import AcommsClient, AcommsError, default_socket


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--socket", default=default_socket(),
                        help="acommsd's unix socket (default: $ACOMMSD_SOCKET or %(default)s)")
    parser.add_argument("--type", action="append", default=[], dest="types",
                        help="only this DCCL type (repeatable; default: every type)")
    parser.add_argument("--src", type=int, help="only messages from this modem id")
    parser.add_argument("--count", type=int, default=0, help="stop after this many messages")
    parser.add_argument("--seconds", type=float, default=0, help="stop after this many seconds")
    parser.add_argument("--json", action="store_true", help="one JSON object per line")
    args = parser.parse_args()

    try:
        acomms = AcommsClient(args.socket)
    except AcommsError as e:
        print(f"subscribe.py: {e}", file=sys.stderr)
        return 1
    subscription = acomms.subscribe(args.types, args.src)
    if args.seconds > 0:
        timer = threading.Timer(args.seconds, subscription.cancel)
        timer.daemon = True
        timer.start()
    signal.signal(signal.SIGINT, lambda *_: subscription.cancel())
    signal.signal(signal.SIGTERM, lambda *_: subscription.cancel())

    print(f"subscribed to {', '.join(args.types) or 'every type'}"
          f"{'' if args.src is None else f' from modem {args.src}'}", file=sys.stderr, flush=True)
    received = 0
    try:
        for message in subscription:
            received += 1
            if args.json:
                print(json.dumps({"type": message.type, "src": message.src, "dest": message.dest,
                                  "receive_time": message.receive_time, "message": message.message}),
                      flush=True)
            else:
                stamp = time.strftime("%H:%M:%S", time.localtime(message.receive_time))
                print(f"{stamp} {message.type} {message.src} -> {message.dest}: "
                      f"{json.dumps(message.message)}", flush=True)
            if args.count and received >= args.count:
                subscription.cancel()
    except AcommsError as e:
        print(f"subscribe.py: {e}", file=sys.stderr)
        return 1
    finally:
        acomms.close()
    print(f"{received} message{'' if received == 1 else 's'} received", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
