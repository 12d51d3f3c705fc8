#!/usr/bin/env python3
"""Names every ctest entry slower than a limit (30 s), from the JUnit XML that
`ctest --output-junit FILE` writes, and always prints the five slowest.

    scripts/check-test-times.py build/ctest-junit.xml --test-dir build

Exit 0 when every entry that ran is within the limit, 1 when one is not
(each named, with its time), 2 on bad input (no such file, not JUnit XML).

The noise of a loaded machine: ctest's times are wall times of entries run
side by side (-j2), on a VM that may be shared, so an entry can take a third
longer beside its neighbour, or several times longer while other builds run.
An entry over the limit is therefore run once more, alone, with the same
environment (`ctest --test-dir DIR -R ^NAME$`), measuring its wall time and
its CPU time (user + system of ctest and every process it waited for, from
getrusage(RUSAGE_CHILDREN)). It fails the check only if both are over the
limit again: a test that really is slow is slow alone too and burns that
CPU, whatever else the machine runs; one made slow by its neighbour or by a
loaded machine is not blamed, and each time is printed. What this misses: a
test slow only because it waits (sleeps, time-outs) uses little CPU and is
named in the list of the slowest, but does not fail the check. Without
--test-dir there is no retry (the self-test's first cases). Entries that
failed are left to ctest, which has already failed the run; entries not run
are ignored.

--self-test checks this script on made-up JUnit files: an entry of 31 s
fails the check and is named, one of 29 s passes; after a retry, an entry
slow alone in wall and CPU time fails, one fast alone, or slow alone but
with little CPU (a loaded machine), passes.
"""
import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

LIMIT_S = 30.0
SHOWN = 5


def read_times(path):
    """[(name, seconds, status)] of the <testcase> elements of a JUnit file."""
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        raise SystemExit(f"check-test-times: cannot read {path}: {e}") from None
    cases = []
    for case in root.iter("testcase"):
        name = case.get("name")
        time = case.get("time")
        if name is None or time is None:
            raise SystemExit(f"check-test-times: {path}: a <testcase> without name or time")
        status = case.get("status", "run")
        if case.find("failure") is not None or case.find("error") is not None:
            status = "fail"
        if case.find("skipped") is not None and status == "run":
            status = "skipped"
        cases.append((name, float(time), status))
    if not cases:
        raise SystemExit(f"check-test-times: {path}: no <testcase> elements")
    return cases


def time_alone(ctest, test_dir, name):
    """Runs one ctest entry alone: (wall s, CPU s), or None if it did not pass."""
    with tempfile.TemporaryDirectory() as tmp:
        junit = os.path.join(tmp, "retry.xml")
        # ctest's regular expressions take a backslash before a special character.
        pattern = "^" + re.sub(r"([][.^$*+?(){}|\\])", r"\\\1", name) + "$"
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        r = subprocess.run([ctest, "--test-dir", test_dir, "-R", pattern, "--output-junit", junit],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        if r.returncode != 0 or not os.path.exists(junit):
            print(r.stdout[-2000:])
            return None
        times = [t for n, t, s in read_times(junit) if n == name and s == "run"]
        return (times[0], cpu) if times else None


def check(junit, limit, test_dir=None, ctest="ctest", out=sys.stdout, alone=time_alone):
    cases = read_times(junit)
    ran = sorted((c for c in cases if c[2] in ("run", "fail")), key=lambda c: -c[1])
    print(f"check-test-times: the {min(SHOWN, len(ran))} slowest of {len(ran)} entries "
          f"({junit}):", file=out)
    for name, t, status in ran[:SHOWN]:
        print(f"  {t:7.1f} s  {name}{'' if status == 'run' else '  (' + status + ')'}", file=out)
    slow = []
    for name, t, status in ran:
        if t <= limit or status != "run":
            continue
        if test_dir is None:
            slow.append(f"{name}: {t:.1f} s")
            continue
        print(f"check-test-times: {name} took {t:.1f} s; running it again alone", file=out)
        out.flush()
        again = alone(ctest, test_dir, name)
        if again is None:
            slow.append(f"{name}: {t:.1f} s, and failed when run again alone")
            continue
        wall, cpu = again
        times = f"{wall:.1f} s alone ({cpu:.1f} s of CPU)"
        if wall > limit and cpu > limit:
            slow.append(f"{name}: {t:.1f} s, {times}")
        else:
            print(f"check-test-times: {name}: {times}, not both over {limit:g} s", file=out)
    for line in slow:
        print(f"check-test-times: slower than {limit:g} s: {line}", file=out)
    if slow:
        print("check-test-times: make the test cheaper or shard it "
              "(sb_add_test(... SHARDS n), tests/CMakeLists.txt)", file=out)
    return 1 if slow else 0


def junit_file(folder, name, cases):
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write('<?xml version="1.0" encoding="UTF-8"?>\n<testsuite name="made-up">\n')
        for case, time in cases:
            f.write(f'  <testcase name="{case}" classname="{case}" time="{time}" status="run"/>\n')
        f.write("</testsuite>\n")
    return path


def self_test():
    import io
    failures = []

    def expect(what, cond):
        if not cond:
            failures.append(what)

    with tempfile.TemporaryDirectory() as tmp:
        few = [(f"fast_{i}", 1.0 + i) for i in range(7)]
        slow = junit_file(tmp, "slow.xml", few + [("test_slow/1", 31.0)])
        text = io.StringIO()
        code = check(slow, LIMIT_S, out=text)
        expect("an entry of 31 s fails the check", code == 1)
        expect("the slow entry is named with its time",
               "slower than 30 s: test_slow/1: 31.0 s" in text.getvalue())
        expect("the five slowest are printed",
               all(f"fast_{i}" in text.getvalue() for i in (3, 4, 5, 6)) and
               "fast_2" not in text.getvalue())
        fine = junit_file(tmp, "fine.xml", few + [("test_ok", 29.0)])
        text = io.StringIO()
        expect("29 s passes", check(fine, LIMIT_S, out=text) == 0)
        expect("nothing named when none is slow", "slower than" not in text.getvalue())
        # The retry's verdict: (wall, CPU) alone.
        for again, want in (((33.0, 32.0), 1), ((12.0, 11.0), 0), ((90.0, 8.0), 0)):
            text = io.StringIO()
            code = check(slow, LIMIT_S, test_dir=tmp, out=text,
                         alone=lambda ctest, test_dir, name, a=again: a)
            expect(f"{again} alone gives exit {want} (got {code}: {text.getvalue()})",
                   code == want)
            if want:
                expect("the retried entry is named with its times",
                       "test_slow/1: 31.0 s, 33.0 s alone (32.0 s of CPU)" in text.getvalue())
        # The retry itself, through a stand-in for ctest that writes the time it is told.
        fake = os.path.join(tmp, "ctest")
        with open(fake, "w") as f:
            f.write("#!/usr/bin/env python3\nimport sys\nargs = sys.argv[1:]\n"
                    "name = args[args.index('-R') + 1].strip('^$').replace('\\\\', '')\n"
                    "path = args[args.index('--output-junit') + 1]\n"
                    "open(path, 'w').write('<testsuite><testcase name=\"' + name + "
                    "'\" time=\"33.0\" status=\"run\"/></testsuite>')\n")
        os.chmod(fake, 0o755)
        again = time_alone(fake, tmp, "test_slow/1")
        expect(f"the entry's time alone is read back (got {again})",
               again is not None and again[0] == 33.0 and 0 <= again[1] < 30)
        bad = os.path.join(tmp, "bad.xml")
        with open(bad, "w") as f:
            f.write("not xml")
        try:
            check(bad, LIMIT_S, out=io.StringIO())
            expect("bad XML is an error", False)
        except SystemExit as e:
            expect("bad XML names the file", "bad.xml" in str(e))
    for f in failures:
        print(f"self-test FAILED: {f}")
    print("self-test passed" if not failures else f"{len(failures)} self-test failures")
    return 1 if failures else 0


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("junit", nargs="?", help="ctest --output-junit FILE")
    p.add_argument("--limit", type=float, default=LIMIT_S, help="seconds (default 30)")
    p.add_argument("--test-dir", help="the build folder, to run a slow entry again alone")
    p.add_argument("--ctest", default="ctest")
    p.add_argument("--self-test", action="store_true")
    a = p.parse_args()
    if a.self_test:
        return self_test()
    if not a.junit:
        p.error("the JUnit file is required")
    return check(a.junit, a.limit, a.test_dir, a.ctest)


if __name__ == "__main__":
    sys.exit(main())
