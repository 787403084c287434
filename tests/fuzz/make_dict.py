#!/usr/bin/env python3
"""A libFuzzer dictionary of dflab's config vocabulary, from the sources.

usage: make_dict.py OUT.dict       (run from the repository root by fuzz.mk)

Every key a getter reads (the string literal after the section argument of
a dfl_cfg_* call in src/ and experiments/) becomes the entries `KEY = ` and
`KEY`; every short lower-case word in a string literal of src/ and
experiments/ (names of kinds, storages, filters, inputs, estimators: the
X-macro name tables of core/names.h and the factories' lists) becomes an
entry, as do the section headers the configs use.  Derived from the code,
the dictionary cannot go stale when a field kind gains a key."""
import os
import re
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
GETTER = re.compile(r'dfl_cfg_[a-z_]+\(\s*[^,;()]+,\s*[^,;()]+,\s*"([a-z_][a-z0-9_]*)"')
WORD = re.compile(r'"([a-z][a-z0-9_]{1,23})"')
SECTION = re.compile(r'^\[([a-z_][a-z0-9_]*)\]\s*$', re.M)


def sources(*dirs):
    for d in dirs:
        for base, _, names in os.walk(os.path.join(ROOT, d)):
            for n in names:
                if n.endswith((".c", ".h", ".cc")):
                    with open(os.path.join(base, n), encoding="utf-8", errors="replace") as fp:
                        yield fp.read()


def main():
    if len(sys.argv) != 2:
        print("usage: make_dict.py OUT.dict", file=sys.stderr)
        return 2
    keys, words, secs = set(), set(), set()
    for text in sources("src", "experiments"):
        keys.update(GETTER.findall(text))
        words.update(WORD.findall(text))
    for base, _, names in os.walk(os.path.join(ROOT, "configs")):
        for n in names:
            if n.endswith(".ini"):
                with open(os.path.join(base, n), encoding="utf-8") as fp:
                    secs.update(SECTION.findall(fp.read()))
    if len(keys) < 50:  # the getter pattern no longer matches the code
        print(f"make_dict: only {len(keys)} keys found; fix GETTER", file=sys.stderr)
        return 1
    entries = sorted({f"{k} = " for k in keys} | keys | words | {f"[{s}]\n" for s in secs})
    tmp = sys.argv[1] + ".tmp"
    with open(tmp, "w") as fp:
        for e in entries:
            esc = e.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\x0a")
            fp.write(f'"{esc}"\n')
    os.replace(tmp, sys.argv[1])
    print(f"make_dict: {len(keys)} keys, {len(words)} words, {len(secs)} sections -> "
          f"{sys.argv[1]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
