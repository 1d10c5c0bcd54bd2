#!/usr/bin/env python3
"""Writes tests/fuzz/scene.dict, the libFuzzer dictionary of the scene loader's harness:

    python3 tests/fuzz/gen_dict.py

Every key and word that docs/scenes.md writes as `code` (keys as "key: ", words as "word"), the
YAML tokens a scene uses (and misuses: anchors, aliases, tags, documents, complex keys), numbers at
the edges (NaN, infinities, 1e308, integer limits, numbers with trailing text), and override
separators (a NUL byte starts an override in the harness's input: "\\x00key.path=").
"""
import os
import re

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.dirname(os.path.dirname(HERE))

YAML = ["{", "}", "[", "]", ", ", ": ", "- ", "\\x0a", "\\x0a  ", "\\x0a    - ", "#", "'", "\\\"",
        "&a ", "*a", "&b [*a, *a, *a, *a]", "!!str ", "!!binary ", "!!map ", "---\\x0a",
        "\\x0a...\\x0a", "%YAML 1.1\\x0a", "? ", "|\\x0a", ">\\x0a", "<<: ", "~", "null",
        "\\x09", "\\x0d", "\\xef\\xbb\\xbf", "\\xff", "\\\\x00"]
NUMBERS = ["0", "-1", "1", "2", "3", "0.5", "1e-3", "2e9", ".nan", ".inf", "-.inf", "nan", "inf",
           "1e308", "1e999", "-1e308", "4.9e-324", "2147483647", "2147483648", "9223372036854775807",
           "18446744073709551616", "1e18", "0x10", "0o7", "7_850", "0,29", "7850kg", "1.5.3",
           "1e", "+-1", "true", "false", "flase", "yes", "no", "on", "off"]


def main():
    with open(os.path.join(SRC, "docs", "scenes.md"), encoding="utf-8") as f:
        doc = f.read()
    keys, words, paths = set(), set(), set()
    section = None
    for line in doc.split("\n"):
        if line.startswith("#"):
            head = line.lstrip("#").strip()
            section = {"Top level": ""}.get(head, head if re.fullmatch(r"[a-z_.]+", head) else None)
            if section in ("sets", "boundary_conditions", "materials"):
                section += "[0]"
            continue
        cells = line.split("|")
        if line.startswith("|") and len(cells) > 2:
            for k in re.findall(r"`([A-Za-z_][A-Za-z0-9_]*)`", cells[1]):
                keys.add(k)
                if section is not None:
                    paths.add(f"{section}.{k}" if section else k)
    for w in re.findall(r"`([A-Za-z_][A-Za-z0-9_.:-]*)`", doc):
        if len(w) <= 40 and w not in keys:
            words.add(w)
    out = ["# libFuzzer dictionary of fuzz_scene_load: written by tests/fuzz/gen_dict.py from",
           "# docs/scenes.md (edit that script, not this file)."]
    out += [f'"{k}: "' for k in sorted(keys)]
    out += [f'"{w}"' for w in sorted(words)]
    out += [f'"\\x00{p}="' for p in sorted(paths)]
    out += [f'"{t}"' for t in YAML + NUMBERS]
    with open(os.path.join(HERE, "scene.dict"), "w", encoding="ascii", newline="\n") as f:
        f.write("\n".join(out) + "\n")
    print(f"gen_dict: {len(keys)} keys, {len(words)} words, {len(paths)} key paths")


if __name__ == "__main__":
    main()
