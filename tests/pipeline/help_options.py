#!/usr/bin/env python3
"""Help true to the code (issue 35): for every subcommand, each option its
parsers accept appears in its --help, and each option --help lists is one its
parsers accept.

The options accepted are the string literals "-x" / "--name" of the files
that parse the command's arguments (PARSERS below: the command's own file and
the shared parsers it calls); the options listed are the "-x" / "--name"
words of `vorball CMD --help`. Both ways are compared, less an explicit
allow-list of names that are not options of the command (ALLOW_*).

usage: help_options.py VORBALL SOURCE_DIR
"""
import os
import re
import subprocess
import sys

# The files whose string literals are the options each command parses
# (cmd_*.c and the shared parsers it calls: vb_pipeline_option in
# pipeline_options.c, vb_cli_input_option in input_options.c,
# vb_cli_periodic_option in vertices_periodic.c, the channels table in
# channel_options.c, the jfa table in lib/jfa_options.c).
INPUT = "cli/input_options.c"
PIPELINE = "cli/pipeline_options.c"
PERIODIC = "cli/vertices_periodic.c"
PARSERS = {
    "vertices": ["cli/cmd_vertices.c", PIPELINE, INPUT, PERIODIC],
    "reference": ["cli/cmd_reference.c", INPUT],
    "verify": ["cli/cmd_verify.c", INPUT, PERIODIC],
    "crosscheck": ["cli/cmd_crosscheck.c", PIPELINE, INPUT],
    "jfa": ["cli/cmd_jfa.c", "lib/jfa_options.c", INPUT],
    "channels": ["cli/cmd_channels.c", "core/discrete/channel_options.c", INPUT],
    "cells": ["cli/cmd_cells.c", INPUT, PERIODIC],
    "bench": ["cli/cmd_bench.c", PIPELINE, INPUT],
    "devices": ["cli/cmd_devices.c"],
}

# Every command's help switch (vb_cli_is_help in cli/cli_common.c, checked
# below), which --help itself need not list: left out on both sides.
HELP_SWITCHES = {"-h", "--help"}
# Per command: aliases the help names once, by their main spelling:
#   channels --centrelines: the British spelling of --centerlines (the
#   option table's alias column).
ALLOW_SOURCE_CMD = {"channels": {"--centrelines"},
                    # the shared periodic parser takes these for vertices alone
                    "verify": {"--traj", "--frames"}}

# Words of the help texts that look like options but are not the command's:
#   -np: `mpirun -np N` in the MPI paragraphs.
ALLOW_HELP = {"-np"}
# Per command: another command's option named in the text:
#   devices: "the device that --device auto selects" (vertices' option).
ALLOW_HELP_CMD = {"devices": {"--device"}}

LITERAL = re.compile(r'"(--?[A-Za-z][A-Za-z0-9-]*)"')
# An option word in running text: starts a word (not inside x-y or a path).
WORD = re.compile(r'(?<![\w/.-])(--?[A-Za-z][A-Za-z0-9-]*)')


def strip_comments(c):
    c = re.sub(r"/\*.*?\*/", " ", c, flags=re.S)
    return re.sub(r"//[^\n]*", " ", c)


def source_options(src, files):
    found = set()
    for f in files:
        text = strip_comments(open(os.path.join(src, f)).read())
        # Help text is printed from these files too: only literals that are a
        # whole string, as strcmp and the option table take them.
        found.update(LITERAL.findall(text))
    return found


def help_options(vorball, cmd):
    p = subprocess.run([vorball, cmd, "--help"], capture_output=True, text=True, timeout=60)
    if p.returncode != 0:
        raise SystemExit("FAIL: vorball %s --help exited %d: %s" % (cmd, p.returncode, p.stderr))
    if not p.stdout.strip():
        raise SystemExit("FAIL: vorball %s --help printed nothing" % cmd)
    return set(WORD.findall(p.stdout))


def main():
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    vorball, src = sys.argv[1], sys.argv[2]
    bad = []
    seen_source, seen_help = set(), set()
    for cmd, files in PARSERS.items():
        raw_accepted, raw_listed = source_options(src, files), help_options(vorball, cmd)
        seen_source |= raw_accepted
        seen_help |= raw_listed
        for o in ALLOW_SOURCE_CMD.get(cmd, set()) - raw_accepted:
            bad.append("%s: allow-listed %s is not in its parsers any more" % (cmd, o))
        for o in ALLOW_HELP_CMD.get(cmd, set()) - raw_listed:
            bad.append("%s: allow-listed %s is not in its --help any more" % (cmd, o))
        accepted = raw_accepted - HELP_SWITCHES - ALLOW_SOURCE_CMD.get(cmd, set())
        listed = raw_listed - HELP_SWITCHES - ALLOW_HELP - ALLOW_HELP_CMD.get(cmd, set())
        if cmd != "devices" and len(accepted) < 2:
            bad.append("%s: only %d options read from %s" % (cmd, len(accepted), files))
        for o in sorted(accepted - listed):
            bad.append("%s: %s is accepted but not in --help" % (cmd, o))
        for o in sorted(listed - accepted):
            bad.append("%s: %s is in --help but not accepted" % (cmd, o))
        print("%s: %d options, in --help and parsed alike" % (cmd, len(accepted & listed))
              if not (accepted ^ listed) else "%s: mismatches" % cmd)
    # The allow-lists stay short: an entry no command uses any more goes.
    common = strip_comments(open(os.path.join(src, "cli/cli_common.c")).read())
    is_help = re.search(r"int vb_cli_is_help\(.*?\n}", common, flags=re.S)
    if not is_help or set(LITERAL.findall(is_help.group(0))) != HELP_SWITCHES:
        bad.append("vb_cli_is_help does not take exactly %s" % sorted(HELP_SWITCHES))
    for o in sorted(ALLOW_HELP - seen_help):
        bad.append("allow-listed %s is in no --help" % o)
    for b in bad:
        print("FAIL: " + b, file=sys.stderr)
    if bad:
        return 1
    print("ok: every command's --help lists exactly the options it parses")
    return 0


if __name__ == "__main__":
    sys.exit(main())
