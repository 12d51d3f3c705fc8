#!/usr/bin/env python3
"""The CI gate's control (configs/ci.json, frames.control) must be able to
see what it normalises: it is no gated job (a job that is its own control has
the ratio 1 whatever happens to it), and its plugin shares no code with any
technique (a slowdown in shared code would divide out, and a slower control
would make every job look faster). Checks both from the sources:
  - the control's technique name is not among the config's techniques;
  - the file that registers it includes nothing from techniques/ but its own
    folder, and its folder registers no other technique.
Usage: check_ci_control.py SOURCE_DIR"""
import json
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
# A TechniqueInfo's name: its designated `.name = "x"`, or the first field of
# a positional one handed to registry.add (plugins outside the tree).
REGISTERED = re.compile(r'(?:registry\.add\(\s*\{\s*|\.name\s*=\s*)"([A-Za-z0-9_]+)"', re.M)


def main():
    root = sys.argv[1]
    with open(os.path.join(root, "configs", "ci.json")) as f:
        config = json.load(f)
    control = config.get("frames", {}).get("control")
    if not control:
        sys.exit("configs/ci.json has no frames.control: the gate compares ratios to it")
    name = control if isinstance(control, str) else control["name"]
    gated = [t if isinstance(t, str) else t["name"] for t in config["techniques"]]
    if name in gated:
        sys.exit(f"configs/ci.json's control {name} is also a gated job: its ratio is 1 by "
                 "construction, and the jobs that share its code hide their slowdowns")

    techniques = os.path.join(root, "techniques")
    home = None
    for family in sorted(os.listdir(techniques)):
        folder = os.path.join(techniques, family)
        if not os.path.isdir(folder):
            continue
        for base, _, files in os.walk(folder):
            for f in files:
                if f.endswith(".cpp"):
                    with open(os.path.join(base, f), encoding="utf-8") as src:
                        if name in REGISTERED.findall(src.read()):
                            home = folder
    if home is None:
        sys.exit(f"no plugin under techniques/ registers the control {name}")
    for base, _, files in os.walk(home):
        for f in files:
            path = os.path.join(base, f)
            with open(path, encoding="utf-8") as src:
                text = src.read()
            others = [n for n in REGISTERED.findall(text) if n != name]
            if others:
                sys.exit(f"{os.path.relpath(path, root)} registers {', '.join(others)} beside "
                         f"the control {name}: the control's folder must be its own")
            for inc in INCLUDE.findall(text):
                top = inc.split("/")[0]
                if os.path.isdir(os.path.join(techniques, top)) and \
                        os.path.join(techniques, top) != home:
                    sys.exit(f"{os.path.relpath(path, root)} includes {inc}: the control must "
                             "share no code with the techniques it normalises")
    print(f"control {name} ({os.path.relpath(home, root)}): no gated job, no shared code")


if __name__ == "__main__":
    main()
