#!/usr/bin/env python3
"""check_layers.py must fail on a broken arrow, and name it.

A checker that passes today's tree proves nothing by itself: it may see no
include at all. So this copies daemon/ and plugins/ of the source tree into
a temporary folder, plants one include of each kind the checker must refuse,
an unlisted room and a public header without a thread sentence (and
includes and headers it must accept), and asserts that the checker fails
and that what it reports beyond the unplanted copy's report is exactly the
planted violations, each named by file:line and its rule.

Usage: check_layers_test.py CHECKER SOURCE_ROOT
"""

import os
import shutil
import subprocess
import sys
import tempfile

# (file, include line, text the report must carry) for each planted violation.
PLANTED = [
    ("daemon/gram/planted_upward.h", '#include "telemetry/telemetry_node.h"',
     "room 'gram' may not include room 'telemetry'"),
    ("daemon/core/planted_upward.cpp", '#include <queue/queue_manager.h>',
     "room 'core' may not include room 'queue'"),
    # node/ need not exist for the rule to hold.
    ("daemon/service/planted_node.cpp", '#include "node/daemon.h"',
     "room 'service' may not include room 'node'"),
    ("daemon/queue/planted_plugin.cpp", '#include "udp/udp_driver.h"',
     "daemon/ includes a plugin's header (drivers/udp)"),
    ("plugins/drivers/sim/planted_private.cpp", '#include "link/link_controller.h"',
     "plugin drivers/sim includes daemon/link/link_controller.h, which is not in the public set"),
    ("plugins/codecs/delta/planted_other_plugin.cpp", '#include "sim/sim_driver.h"',
     "plugin codecs/delta includes another plugin's header (drivers/sim)"),
]
# Includes the layers allow: planting them must change nothing.
ACCEPTED = [
    ("daemon/link/planted_down.h", '#include "queue/queue_manager.h"'),
    ("plugins/drivers/udp/planted_public.cpp", '#include "link/driver.h"'),
]
UNKNOWN_ROOM = "daemon/planted_room/planted.h"
# Public headers and their thread sentence: (header, its top comment, who includes it).
SILENT_PUBLIC = ("daemon/core/planted_silent.h", "// A planted public header.",
                 ("daemon/queue/planted_silent_user.cpp", '#include "core/planted_silent.h"'))
SPOKEN_PUBLIC = ("daemon/core/planted_spoken.h", "// A planted public header. Thread-safe: it holds nothing.",
                 ("daemon/queue/planted_spoken_user.cpp", '#include "core/planted_spoken.h"'))
SILENT_PRIVATE = ("daemon/core/planted_private.h", "// A planted header only its room includes.",
                  ("daemon/core/planted_private_user.cpp", '#include "core/planted_private.h"'))


def run(checker, root):
    result = subprocess.run([sys.executable, checker, root], capture_output=True, text=True)
    return result.returncode, [line for line in result.stdout.splitlines() if not line.startswith("check_layers:")]


def plant(root, path, include, comment="// planted by check_layers_test.py"):
    full = os.path.join(root, path)
    os.makedirs(os.path.dirname(full), exist_ok=True)
    with open(full, "w", encoding="utf-8") as f:
        # Line 3, so that a report naming line 1 is caught.
        f.write(comment + "\n#pragma once\n" + include + "\n")


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    checker, source = os.path.abspath(argv[1]), os.path.abspath(argv[2])
    failures = []
    with tempfile.TemporaryDirectory(prefix="check_layers_") as copy:
        for top in ("daemon", "plugins"):
            shutil.copytree(os.path.join(source, top), os.path.join(copy, top))
        _, before = run(checker, copy)
        for path, include, _ in PLANTED:
            plant(copy, path, include)
        for path, include in ACCEPTED:
            plant(copy, path, include)
        plant(copy, UNKNOWN_ROOM, "")
        for header, comment, (user, include) in (SILENT_PUBLIC, SPOKEN_PUBLIC, SILENT_PRIVATE):
            plant(copy, header, "", comment)
            plant(copy, user, include)
        code, after = run(checker, copy)
    new = [line for line in after if line not in before]
    if code != 1:
        failures.append(f"the checker exited {code} on planted violations, not 1")
    for path, include, rule in PLANTED:
        expected = f"{path}:3: {include}: "
        if not any(line.startswith(expected) and rule in line for line in new):
            failures.append(f"not reported: {path}:3 ({rule})")
    if not any(line.startswith("daemon/planted_room/: room 'planted_room' is not in the layer table")
               for line in new):
        failures.append("not reported: daemon/planted_room/ as a room missing from the layer table")
    silent = f"{SILENT_PUBLIC[0]}:1: public header (included by {SILENT_PUBLIC[2][0]}:3) states no thread rule"
    if not any(line.startswith(silent) for line in new):
        failures.append(f"not reported: {SILENT_PUBLIC[0]}, a public header without a thread sentence")
    for path in [path for path, _ in ACCEPTED] + [SPOKEN_PUBLIC[0], SILENT_PRIVATE[0]] + \
            [SPOKEN_PUBLIC[2][0], SILENT_PRIVATE[2][0], SILENT_PUBLIC[2][0]]:
        for line in new:
            if line.startswith(path):
                failures.append(f"refused, but the rules allow it: {line}")
    expected_count = len(PLANTED) + 2
    if len(new) != expected_count:
        failures.append(f"{len(new)} new reports, expected {expected_count}:\n  " + "\n  ".join(new))
    for failure in failures:
        print("FAIL:", failure)
    if not failures:
        print(f"ok: the checker fails on the {expected_count} planted violations and names each:")
        for line in new:
            print("  " + line)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
