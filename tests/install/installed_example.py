"""The shipped example technique, docs/examples/my_pcf, as a user gets it:
its installed copy (<prefix>/share/doc/shadowbench/examples/my_pcf) is
built against the installed plugin API and shadow-map kit alone, loaded
through $SHADOWBENCH_PLUGIN_PATH, and run beside the built-in pcf_box with
the same parameters. It is pcf_box's filter written again on the kit, so the
two must measure the same: their visibility RMSE against the one reference
agrees to 1e-6. Called by install_and_relocate.py on its moved prefix."""
import glob
import json
import os

EXAMPLE = os.path.join("share", "doc", "shadowbench", "examples", "my_pcf")
# The example's own files, as installed.
EXAMPLE_FILES = ("CMakeLists.txt", "my_pcf.cpp", "my_pcf.json", "README.md")
# The project's warnings, as errors: the kit's headers must build cleanly
# in a plugin as strict as the built-ins.
WARNINGS = "-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion -Werror"
TOLERANCE = 1e-6
# pcf_box's parameters that my_pcf lacks, at the values my_pcf's filter is.
# pcf_box's parameters my_pcf lacks, at what my_pcf implements: nearest taps,
# no receiver plane, and the kit's contact option off (with_contact_option,
# which the template does not apply).
PCF_BOX_ONLY = {"filter": "nearest", "receiver_plane_bias": False, "contact": False,
                "contact_length": 0.5, "contact_steps": 16, "contact_thickness": 0.05}


def small_config(installed_config, out_path):
    """The installed my_pcf.json at a small resolution and sample count;
    its techniques and their parameters untouched."""
    with open(installed_config) as f:
        config = json.load(f)
    params = {t["name"]: t.get("params", {}) for t in config["techniques"]
              if isinstance(t, dict)}
    if "my_pcf" not in params or "pcf_box" not in params:
        raise SystemExit(f"{installed_config} does not run my_pcf beside pcf_box: {params}")
    if params["my_pcf"] != params["pcf_box"]:
        raise SystemExit(f"{installed_config}: my_pcf and pcf_box differ in parameters: "
                         f"{params['my_pcf']} vs {params['pcf_box']}")
    config["resolutions"] = [[96, 72]]
    config["frames"] = {"warmup": 0, "timed": 1, "control": None}
    config["reference"] = {"spp": 16, "seed": 1, "cache": False}
    with open(out_path, "w") as f:
        json.dump(config, f)


def visibility_rmse(run_dir):
    """technique name -> (status, params, all RMSE, penumbra RMSE)."""
    found = {}
    for path in glob.glob(os.path.join(run_dir, "records", "*.json")):
        with open(path) as f:
            r = json.load(f)
        v = r.get("metrics", {}).get("visibility", {})
        found[r["technique"]["name"]] = (
            r["status"], r["technique"]["params"], v.get("all", {}).get("rmse"),
            v.get("penumbra", {}).get("rmse"))
    return found


def build_and_compare(prefix, work, cmake, cxx, env, run):
    """`run(what, *cmd, env=None, cwd=None)` runs a command, failing the
    test on a non-zero exit, and returns its output."""
    source = os.path.join(prefix, EXAMPLE)
    for name in EXAMPLE_FILES:
        if not os.path.isfile(os.path.join(source, name)):
            raise SystemExit(f"the install lacks {os.path.join(EXAMPLE, name)}")
    build = os.path.join(work, "my_pcf-build")
    run("configuring the installed example my_pcf", cmake, "-S", source, "-B", build,
        "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_COMPILER=" + cxx,
        "-DCMAKE_CXX_FLAGS=" + WARNINGS, "-DCMAKE_PREFIX_PATH=" + prefix, env=env)
    run("building it", cmake, "--build", build, env=env)

    config = os.path.join(work, "my_pcf_small.json")
    small_config(os.path.join(source, "my_pcf.json"), config)
    run_dir = os.path.join(work, "my_pcf-run")
    env_with_plugin = dict(env, SHADOWBENCH_PLUGIN_PATH=build)
    run("my_pcf beside pcf_box", os.path.join(prefix, "bin", "shadowbench"), "run", config,
        "--out", run_dir, "--no-cache", "--quiet", env=env_with_plugin, cwd=work)
    found = visibility_rmse(run_dir)
    print("status, params, visibility RMSE (all, penumbra):",
          json.dumps(found, sort_keys=True))
    for name in ("my_pcf", "pcf_box", "none"):
        if name not in found or found[name][0] != "ok":
            raise SystemExit(f"no ok record of {name}: {found.get(name)}")
    mine, builtin, none = found["my_pcf"], found["pcf_box"], found["none"]
    # Every parameter my_pcf has, pcf_box has with the same value; pcf_box's
    # others are at what my_pcf implements (PCF_BOX_ONLY).
    shared = {k: builtin[1].get(k) for k in mine[1]}
    rest = {k: v for k, v in builtin[1].items() if k not in mine[1]}
    if shared != mine[1] or rest != PCF_BOX_ONLY:
        raise SystemExit(f"the records' parameters differ: my_pcf {mine[1]}, pcf_box {builtin[1]}")
    for i, region in ((2, "all"), (3, "penumbra")):
        if not abs(mine[i] - builtin[i]) <= TOLERANCE:
            raise SystemExit(f"my_pcf's {region} RMSE {mine[i]!r} is not pcf_box's "
                             f"{builtin[i]!r} to {TOLERANCE}")
        # Both cast a real shadow: equal because right, not because empty.
        if not mine[i] < 0.5 * none[i]:
            raise SystemExit(f"my_pcf's {region} RMSE {mine[i]!r} is not under half of "
                             f"no shadows' ({none[i]!r})")
