#!/usr/bin/env python3
"""Checks how the comparison section marks a row's target (scripts/sections/
compare/compare_methods.py), on rows made up here:

- a row whose build did not meet its target (target_met 0) is marked "not
  met" with its cells over, and listed under "Targets not met";
- a row whose build met it by its own estimate while the study's L∞ over its
  error points did not (target_met 1, target_linf_met 0) is marked "met by
  the fit's estimate" with that L∞, and listed under "Targets met by the
  build's own estimate but not by the study's L∞";
- a row met both ways, and a row without a target (empty cells), get no mark
  and no line.

usage: check_targets.py.  Prints "ok" and exits 0, or what failed and 1."""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "scripts"))
from sections.compare import compare_methods as cm  # noqa: E402


def row(method, setting, met, over, linf_met, linf):
    return {"method": method, "shape": "s_x", "setting": setting, "target": "0.01" if met else "",
            "target_met": met, "target_over": over, "target_linf_met": linf_met,
            "linf": linf}


def main():
    bad = []

    def want(cond, what):
        if not cond:
            bad.append(what)

    unmet = row("m_a", "eps=1e-3", "0", "4", "0", "0.02")
    est = row("m_b", "eps=1e-2", "1", "0", "0", "0.0107")
    both = row("m_c", "eps=1e-2", "1", "0", "1", "0.008")
    none = row("m_d", "res=8", "", "", "", "0.5")
    s = cm._setting(unmet)
    want("not met: 4 cells over" in s and "estimate" not in s, "unmet row's setting: %r" % s)
    s = cm._setting(est)
    want("met by the fit's estimate; L∞ 0.0107" in s and "not met" not in s,
         "estimate-only row's setting: %r" % s)
    want(cm._setting(both) == "eps=1e-2", "row met both ways is marked: %r" % cm._setting(both))
    want(cm._setting(none) == "res=8", "row without a target is marked: %r" % cm._setting(none))
    t = cm._targets([unmet, est, both, none])
    want("Targets not met" in t and "m_a on s_x eps=1e-3: 4 cells over" in t,
         "unmet row not listed: %r" % t)
    want("Targets met by the build's own estimate but not by the study's L∞" in t and
         "m_b on s_x eps=1e-2: L∞ 0.0107 > 0.01" in t, "estimate-only row not listed: %r" % t)
    want("m_c" not in t and "m_d" not in t, "a row met both ways or without target listed: %r" % t)
    want(cm._targets([both, none]) == "", "lines without a row to list: %r" % cm._targets([both, none]))
    if bad:
        print("\n".join(bad))
        return 1
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
