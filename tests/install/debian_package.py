#!/usr/bin/env python3
"""Builds the Debian package of a shadowbench build with CPack and checks it
as a user's machine would take it: its control fields (Depends computed by
dpkg-shlibdeps, with python3-matplotlib for the charts), its files, apt's
resolution of its dependencies on this Debian (docs/Dockerfile's own
apt-get line, in simulation), and the binary unpacked with `dpkg -x`
running docs/Dockerfile's commands from there. Prints the package's size
and the time each step took. Run by ctest (tests/install/CMakeLists.txt)."""
import argparse
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import time


def run(what, *cmd, env=None, cwd=None):
    started = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=cwd)
    print(f"{what}: {time.monotonic() - started:.1f} s (exit {r.returncode})")
    if r.returncode != 0:
        sys.exit(f"{what} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r.stdout


def dockerfile_steps(path):
    """The apt-get install arguments and the shadowbench commands of the
    Dockerfile's RUN lines."""
    install, commands = None, []
    for line in open(path):
        if not line.startswith("RUN "):
            continue
        for part in line[4:].split("&&"):
            words = shlex.split(part)
            if words[:2] == ["apt-get", "install"]:
                install = words[2:]
            elif words and words[0] == "shadowbench":
                commands.append(words[1:])
    if install is None or not commands:
        sys.exit(f"{path}: no 'apt-get install' or no shadowbench command in its RUN lines")
    return install, commands


def main():
    a = argparse.ArgumentParser()
    for name in ("build", "work", "dockerfile"):
        a.add_argument("--" + name, required=True)
    a = a.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    started = time.monotonic()
    run("cpack -G DEB", "cpack", "-G", "DEB", "--config",
        os.path.join(a.build, "CPackConfig.cmake"), "-B", a.work)
    debs = glob.glob(os.path.join(a.work, "shadowbench_*_amd64.deb"))
    if len(debs) != 1:
        sys.exit(f"expected one shadowbench_<version>_amd64.deb, found {debs}")
    deb = debs[0]
    print(f"package: {os.path.basename(deb)}, {os.path.getsize(deb) / 1e6:.2f} MB")

    fields = run("dpkg-deb -f", "dpkg-deb", "-f", deb, "Package", "Version", "Architecture",
                 "Depends", "Recommends")
    depends = re.search(r"^Depends: (.*)$", fields, re.M)
    if not depends:
        sys.exit(f"no Depends:\n{fields}")
    needed = [d.strip().split()[0] for d in depends.group(1).split(",")]
    print("Depends:", ", ".join(needed))
    # dpkg-shlibdeps found the libraries the binaries link; the charts' own.
    for package in ("python3-matplotlib", "libosmesa6", "libopenimageio2.4", "libtbb12",
                    "libc6", "libstdc++6"):
        if package not in needed:
            sys.exit(f"Depends lacks {package}: {depends.group(1)}")
    if not any(p.startswith("libembree3") for p in needed):
        sys.exit(f"Depends lacks Embree 3: {depends.group(1)}")
    # Debian policy 5.6.13: a one-line synopsis, then the extended
    # description, every line of it starting with a space; none a list's ';'.
    # (dpkg-deb -f with one field prints its value alone.)
    description = run("dpkg-deb -f Description", "dpkg-deb", "-f", deb,
                      "Description").rstrip("\n").split("\n")
    synopsis, extended = description[0], description[1:]
    if not synopsis.strip() or synopsis[0].isspace() or len(extended) < 2:
        sys.exit(f"no synopsis and extended description:\n{description}")
    for line in extended:
        if not line.startswith(" ") or line.lstrip().startswith(";"):
            sys.exit(f"the Description's line {line!r} does not start with one space and text:"
                     f"\n" + "\n".join(description))
    files = run("dpkg-deb -c", "dpkg-deb", "-c", deb)
    for path in ("./usr/bin/shadowbench", "./usr/lib/shadowbench/libshadowbench_core.so",
                 "./usr/lib/shadowbench/plugins/shadow_map.so",
                 "./usr/share/shadowbench/plot_charts.py",
                 "./usr/share/shadowbench/configs/quick.json",
                 "./usr/share/man/man1/shadowbench.1.gz",
                 "./usr/share/bash-completion/completions/shadowbench",
                 "./usr/share/doc/shadowbench/README.md",
                 "./usr/lib/shadowbench/libshadowbench_shadow_kit.a",
                 "./usr/include/shadowbench/common/map_lookup.h",
                 "./usr/share/doc/shadowbench/examples/my_pcf/my_pcf.cpp"):
        if path not in files:
            sys.exit(f"the package lacks {path}")

    # docs/Dockerfile's install, in simulation: every dependency resolves
    # from Debian 12's archive (or is installed already).
    install, commands = dockerfile_steps(a.dockerfile)
    install = [deb if w.startswith("/tmp/shadowbench_") else w for w in install]
    if deb not in install:
        sys.exit(f"{a.dockerfile}: its apt-get install does not name the package: {install}")
    simulated = run("apt-get install --simulate (the Dockerfile's)", "apt-get", "install",
                    "--simulate", *install)
    if "shadowbench" not in simulated:
        sys.exit(f"apt-get would not install shadowbench:\n{simulated}")

    # Unpacked, it runs from where dpkg put it: the Dockerfile's commands.
    root = os.path.join(a.work, "root")
    run("dpkg -x", "dpkg", "-x", deb, root)
    exe = os.path.join(root, "usr", "bin", "shadowbench")
    env = {k: v for k, v in os.environ.items() if not k.startswith("SHADOWBENCH_")}
    for args in commands:
        out = run("shadowbench " + " ".join(args), exe, *args, env=env)
        if args == ["--version"] and f"plugins: {root}/usr/lib/shadowbench/plugins" not in out:
            sys.exit(f"--version does not name the unpacked plugins:\n{out}")
        if args == ["list", "--names"] and "shadow_map" not in out.split():
            sys.exit(f"list --names lacks shadow_map:\n{out}")
    man = run("man -l", "man", "-l", os.path.join(root, "usr/share/man/man1/shadowbench.1.gz"),
              env=dict(env, MANWIDTH="100"))
    # man's bold and underline are overstrikes (x\bx) when not on a terminal.
    man = re.sub(r".\x08", "", man).replace("\u2010", "-").replace("\u2212", "-")
    for section in ("SHADOWBENCH_PLUGIN_PATH", "compare-builds", "--normalize", "EXAMPLES"):
        if section not in man:
            sys.exit(f"the man page lacks {section}:\n{man[:3000]}")
    print(f"package test: {time.monotonic() - started:.1f} s in all")


if __name__ == "__main__":
    main()
