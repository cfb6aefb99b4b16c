#!/usr/bin/env python3
"""Runs one command and records its wall time and peak memory, as /usr/bin/time -v
would (which a bare machine may lack).

usage: measure.py OUT.json [--stdin FILE] [--stdout FILE] [--stderr FILE]
                  [--timeout S] [--env NAME=VALUE]... -- COMMAND [ARG...]

OUT.json gets: the command, exit status, elapsed wall seconds, user and system
CPU seconds, the peak resident set size in KiB and whether it was killed at the
timeout. The peak ('max_rss_kib') is the largest VmHWM read from
/proc/PID/status every 10 ms while the command runs (the high-water mark of
the command's own memory after exec); where /proc gives none it is wait4's
ru_maxrss ('max_rss_from' says which), which on Linux is at least this
Python's own size at the fork (exec keeps the forked copy's high-water mark). The command's own exit status is measure.py's. Standard library only.
"""
import json
import os
import signal
import subprocess
import sys
import threading
import time


def main(argv):
    if len(argv) < 3 or "--" not in argv:
        sys.exit(__doc__)
    out = argv[0]
    k = argv.index("--")
    opts, cmd = argv[1:k], argv[k + 1:]
    if not cmd:
        sys.exit(__doc__)
    fin = fout = ferr = None
    timeout = None
    env = dict(os.environ)
    extra_env = {}
    i = 0
    while i < len(opts):
        o = opts[i]
        v = opts[i + 1] if i + 1 < len(opts) else None
        if v is None:
            sys.exit(__doc__)
        if o == "--stdin":
            fin = v
        elif o == "--stdout":
            fout = v
        elif o == "--stderr":
            ferr = v
        elif o == "--timeout":
            timeout = float(v)
        elif o == "--env":
            name, _, val = v.partition("=")
            env[name] = val
            extra_env[name] = val
        else:
            sys.exit(__doc__)
        i += 2
    si = open(fin, "rb") if fin else None
    so = open(fout, "wb") if fout else None
    se = open(ferr, "wb") if ferr else None
    t0 = time.perf_counter()
    p = subprocess.Popen(cmd, stdin=si, stdout=so, stderr=se, env=env, start_new_session=True)
    killed = {"v": False}

    def kill():
        killed["v"] = True
        try:
            os.killpg(p.pid, signal.SIGKILL)
        except OSError:
            pass

    timer = threading.Timer(timeout, kill) if timeout else None
    if timer:
        timer.start()
    hwm = {"kib": None}

    def poll():
        path = "/proc/%d/status" % p.pid
        while True:
            try:
                # WNOHANG-free peek: waitid with WNOWAIT leaves the child to wait4.
                done = os.waitid(os.P_PID, p.pid, os.WEXITED | os.WNOHANG | os.WNOWAIT)
            except ChildProcessError:
                return
            try:
                with open(path) as f:
                    for line in f:
                        if line.startswith("VmHWM:"):
                            v = int(line.split()[1])
                            if hwm["kib"] is None or v > hwm["kib"]:
                                hwm["kib"] = v
            except (OSError, ValueError, IndexError):
                pass
            if done is not None:
                return
            time.sleep(0.01)

    poller = threading.Thread(target=poll, daemon=True)
    poller.start()
    poller.join()
    _, status, ru = os.wait4(p.pid, 0)
    wall = time.perf_counter() - t0
    if timer:
        timer.cancel()
    p.returncode = os.waitstatus_to_exitcode(status) if hasattr(os, "waitstatus_to_exitcode") else (
        -(status & 0x7f) if status & 0x7f else status >> 8)
    for f in (si, so, se):
        if f:
            f.close()
    rec = {
        "cmd": cmd, "env": extra_env, "stdin": fin, "stdout": fout, "rc": p.returncode,
        "wall_s": round(wall, 4), "user_s": round(ru.ru_utime, 4), "sys_s": round(ru.ru_stime, 4),
        "max_rss_kib": hwm["kib"] if hwm["kib"] is not None else ru.ru_maxrss,
        "max_rss_from": "VmHWM" if hwm["kib"] is not None else "ru_maxrss",
        "ru_maxrss_kib": ru.ru_maxrss, "timed_out": killed["v"], "timeout_s": timeout,
    }
    with open(out, "w") as f:
        json.dump(rec, f)
        f.write("\n")
    return p.returncode if p.returncode >= 0 else 128 - p.returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
