#!/usr/bin/env python3
"""The layers of DESIGN.md, checked on every #include under daemon/ and plugins/.

The problem: DESIGN.md draws the arrows ("Dependencies point down this list
and never up: util < core < store < dccl < queue < mac < link < route; ...")
and says plugins use only the public headers of core, dccl, link and gram.
A drawing is kept by reviewers' memory; one upward include compiles fine and
quietly welds two layers together. So this script reads every include line
and fails, naming file:line and the rule, when

  1. a room of daemon/ includes a header of a room it may not use
     (ALLOWED below: one entry per room, the DESIGN sentence beside it);
  2. a room of daemon/ includes a plugin's header (the daemon picks plugins
     by name and never includes one);
  3. a plugin (plugins/drivers/*, plugins/codecs/*) includes a daemon header
     outside PLUGIN_PUBLIC, or another plugin's header;
  4. a folder under daemon/ is not in ALLOWED (a new room must be placed),
     or PLUGIN_PUBLIC names a header that no longer exists (a stale table
     would let a renamed private header through);
  5. a public header (one another room or a plugin includes, or one in
     PLUGIN_PUBLIC) says nothing about threads in its top comment: STYLE.md
     asks each to state its thread-safety in one sentence at the top. (The
     check is that the comment before the first line of code speaks of
     threads at all; whether the sentence is true is the reviewer's.)

An include is resolved as the compiler does for the project's include
directories (the including file's folder, then daemon/, plugins/drivers/,
plugins/codecs/); one that resolves to no file there (a system header, a
generated acomms/*.pb.h) is outside the check, unless its first folder names
a room or a plugin, so a room that does not exist yet (node/, route/) is
checked too.

Usage: check_layers.py SOURCE_ROOT   (exit 0: clean; 1: violations, listed)
"""

import os
import re
import sys

# Which rooms each room of daemon/ may include, besides itself. From
# DESIGN.md ("Layout" and the sentences under it):
#   "Dependencies point down this list and never up: util < core < store <
#    dccl < queue < mac < link < route" -> each takes every room before it;
#   "telemetry uses dccl, queue and core" -> those and what lies under them
#    (util, store), never mac, link, route or gram;
#   "gram uses only util and core (a leaf the simulator may use)";
#   "eval may use any layer" -> every layer, but not the daemon's own
#    assembly (node) or its gRPC face (service);
#   "node assembles all of them; service may use all" -> node takes every
#    layer and service; service takes every layer, never node (node builds
#    the service, not the other way round);
#   eval is "linked by acommsctl and tests, never by acommsd", so nothing
#    that acommsd is made of (node, service, main) includes it.
# "main" is daemon/ itself: main.cpp (and, until they move to node/, the
# assembly files beside it).
LAYERS = ["util", "core", "store", "dccl", "queue", "mac", "link", "route"]
ALLOWED = {
    "util": set(),
    "core": {"util"},
    "store": {"util", "core"},
    "dccl": {"util", "core", "store"},
    "queue": {"util", "core", "store", "dccl"},
    "mac": {"util", "core", "store", "dccl", "queue"},
    "link": {"util", "core", "store", "dccl", "queue", "mac"},
    "route": {"util", "core", "store", "dccl", "queue", "mac", "link"},
    "telemetry": {"util", "core", "store", "dccl", "queue"},
    "gram": {"util", "core"},
    "eval": set(LAYERS) | {"telemetry", "gram"},
    "service": set(LAYERS) | {"telemetry", "gram"},
    "node": set(LAYERS) | {"telemetry", "gram", "service"},
    "main": set(LAYERS) | {"telemetry", "gram", "service", "node"},
}

# The daemon headers a plugin may include: the public face of core, dccl,
# link and gram (DESIGN.md: "Plugins use the public headers of core, dccl,
# link and gram"; STYLE.md names link/driver.h, dccl/field_codec.h,
# dccl/registry.h and gram's model API as the contract).
ANY = None  # the whole room
PLUGIN_PUBLIC = {
    # util/ is the small things written once for everyone ("small shared
    # helpers with no project dependencies"): all of it.
    "util": ANY,
    # Time and the core thread a driver runs on, and where the vehicle is
    # (node_position.h: "read by whoever needs the vehicle's position").
    "core": {"clock.h", "scheduler.h", "core_thread.h", "node_position.h"},
    # The codec interface and registry, what a codec's interface exposes
    # (bits, options, errors), how plugin codecs register, and the two
    # pieces of DCCL arithmetic a codec builds on: the bounded-number rule
    # and the arithmetic coder (shared with telemetry by design).
    "dccl": {"field_codec.h", "registry.h", "plugin_codecs.h", "bitstream.h", "options.h", "error.h",
             "numeric.h", "arithmetic_coder.h"},
    # The driver interface, its registry, the shared transmit/receive
    # sequence and the rules it applies, driver-specific transmissions, the
    # rate table and slot budget (driver.h's timing contract), and the
    # transports.
    "link": {"driver.h", "driver_registry.h", "driver_sequence.h", "transmission_rules.h",
             "driver_specific.h", "rate_table.h", "slot_budget.h", "transport_state.h",
             "serial_transport.h", "tcp_client_transport.h", "udp_transport.h"},
    # GRAM's model API: transmission loss and arrivals from an Environment,
    # the worker pool and an engine's face, TL lookup and link physics for a
    # simulated channel, and checking/importing an environment.
    "gram": {"transmission_loss.h", "arrivals.h", "cancel_token.h", "model_pool.h", "model_engine.h",
             "tl_lookup.h", "link_physics.h", "reception_curve.h", "environment_validation.h",
             "bellhop_import.h"},
}

SOURCE_SUFFIXES = (".h", ".hpp", ".cpp", ".cc", ".ipp", ".inc")
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
PLUGIN_KINDS = ("drivers", "codecs")


def rel(root, path):
    return os.path.relpath(path, root).replace(os.sep, "/")


def owner(root, path):
    """('room', name) for daemon/, ('plugin', 'drivers/sim') for a plugin, or None."""
    parts = rel(root, path).split("/")
    if parts[0] == "daemon":
        return ("room", parts[1] if len(parts) > 2 else "main")
    if parts[0] == "plugins" and len(parts) > 2 and parts[1] in PLUGIN_KINDS:
        return ("plugin", parts[1] + "/" + parts[2]) if len(parts) > 3 else ("plugin", parts[1])
    return None


def plugin_names(root):
    names = {}
    for kind in PLUGIN_KINDS:
        base = os.path.join(root, "plugins", kind)
        if os.path.isdir(base):
            for name in sorted(os.listdir(base)):
                if os.path.isdir(os.path.join(base, name)):
                    names[name] = kind + "/" + name
    return names


def resolve(root, including, header, quoted):
    """The included file's path if it is in the tree, else None."""
    bases = [os.path.dirname(including)] if quoted else []
    bases += [os.path.join(root, "daemon")] + [os.path.join(root, "plugins", k) for k in PLUGIN_KINDS]
    for base in bases:
        candidate = os.path.normpath(os.path.join(base, header))
        if os.path.isfile(candidate):
            return candidate
    return None


def target_of(root, including, header, quoted, plugins):
    """(kind, name, daemon-relative header) of an include, or None if outside the check."""
    path = resolve(root, including, header, quoted)
    if path is not None:
        who = owner(root, path)
        if who is None:
            return None
        inside = rel(root, path)
        return who + (inside[len("daemon/"):] if who[0] == "room" else inside,)
    first = header.split("/")[0]
    if "/" in header and first in ALLOWED:
        return ("room", first, header)
    if "/" in header and first in plugins:
        return ("plugin", plugins[first], header)
    return None


def sources(root):
    for top in ("daemon", "plugins"):
        for folder, dirs, files in os.walk(os.path.join(root, top)):
            dirs.sort()
            for name in sorted(files):
                if name.endswith(SOURCE_SUFFIXES):
                    yield os.path.join(folder, name)


def allowed_text(room):
    return ", ".join(r for r in LAYERS + ["telemetry", "gram", "service", "node"] if r in ALLOWED[room]) or "nothing"


def top_comment(path):
    """The comment lines before the first line of code (#pragma once aside)."""
    comment = []
    with open(path, encoding="utf-8", errors="replace") as f:
        for line in f:
            text = line.strip()
            if text.startswith("//"):
                comment.append(text)
            elif text and text != "#pragma once":
                break
    return "\n".join(comment)


def check(root):
    problems = []
    plugins = plugin_names(root)
    daemon = os.path.join(root, "daemon")
    for name in sorted(os.listdir(daemon)) if os.path.isdir(daemon) else []:
        if os.path.isdir(os.path.join(daemon, name)) and name not in ALLOWED:
            problems.append(f"daemon/{name}/: room '{name}' is not in the layer table (tests/structure/"
                            f"check_layers.py ALLOWED): place it in DESIGN.md's order and list what it may use")
    for room, headers in sorted(PLUGIN_PUBLIC.items()):
        for header in sorted(headers or []):
            if not os.path.isfile(os.path.join(daemon, room, header)):
                problems.append(f"daemon/{room}/{header}: listed as public to plugins (PLUGIN_PUBLIC) but "
                                f"missing: update the table")
    # daemon-relative public header -> where it is first included from outside its room
    public_headers = {f"{room}/{header}": "PLUGIN_PUBLIC"
                      for room, headers in PLUGIN_PUBLIC.items() for header in headers or []}
    checked = 0
    for path in sources(root):
        who = owner(root, path)
        if who is None:
            continue
        with open(path, encoding="utf-8", errors="replace") as f:
            lines = f.readlines()
        for number, line in enumerate(lines, 1):
            m = INCLUDE.match(line)
            if not m:
                continue
            checked += 1
            header = m.group(2)
            target = target_of(root, path, header, m.group(1) == '"', plugins)
            if target is None:
                continue
            where = f"{rel(root, path)}:{number}: {' '.join(m.group(0).split())}: "
            kind, name, inside = target
            if kind == "room" and (who[0] == "plugin" or name != who[1]):
                public_headers.setdefault(inside, where.split(": ")[0])
            if who[0] == "room":
                room = who[1]
                if kind == "plugin":
                    problems.append(where + f"daemon/ includes a plugin's header ({name}); the daemon "
                                    f"picks plugins by their registered name and never includes one")
                elif name != room and room in ALLOWED and name not in ALLOWED[room]:
                    problems.append(where + f"room '{room}' may not include room '{name}' (DESIGN.md "
                                    f"layers: {room} may use {allowed_text(room)})")
            else:
                plugin = who[1]
                if kind == "plugin":
                    if name != plugin:
                        problems.append(where + f"plugin {plugin} includes another plugin's header "
                                        f"({name}); plugins share code only through the daemon's public headers")
                    continue
                public_room, _, file = inside.partition("/")
                public = PLUGIN_PUBLIC.get(public_room, set())
                if public is not ANY and file not in public:
                    problems.append(where + f"plugin {plugin} includes daemon/{inside}, which is not in "
                                    f"the public set a plugin may use (tests/structure/check_layers.py "
                                    f"PLUGIN_PUBLIC)")
    for inside, user in sorted(public_headers.items()):
        path = os.path.join(daemon, inside)
        if os.path.isfile(path) and not re.search(r"thread", top_comment(path), re.IGNORECASE):
            problems.append(f"daemon/{inside}:1: public header (included by {user}) states no thread rule in "
                            f"its top comment (STYLE.md: each public header states its thread-safety in "
                            f"one sentence)")
    return problems, checked


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    root = os.path.abspath(argv[1])
    if not os.path.isdir(os.path.join(root, "daemon")):
        print(f"check_layers: {root} has no daemon/ folder", file=sys.stderr)
        return 2
    problems, checked = check(root)
    for problem in problems:
        print(problem)
    if problems:
        print(f"check_layers: {len(problems)} broken rule(s) in {checked} includes")
        return 1
    print(f"check_layers: ok, {checked} includes under daemon/ and plugins/ follow the layers, "
          f"and every public header states its thread rule")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
