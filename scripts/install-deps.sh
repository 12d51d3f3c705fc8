#!/usr/bin/env bash
# Installs the Debian 12 packages shadowbench builds and tests with.
# Skips everything already installed, so it is cheap to call twice.
#   scripts/install-deps.sh            what building and running need
#   scripts/install-deps.sh --test     that and what the tests need
#   scripts/install-deps.sh --test-only  only what the tests need beyond
#                                      building (test.sh installs it while
#                                      the build runs)
set -euo pipefail

packages=()
build_packages=(
  build-essential cmake pkg-config ninja-build
  libosmesa6-dev libegl-dev libegl1-mesa-dev libgl1-mesa-dri
  python3-glad python3-matplotlib
  libopenimageio-dev
  libtinygltf-dev libglm-dev nlohmann-json3-dev
  libembree-dev libtbb-dev libpolyclipping-dev libboost-dev libssl-dev libsqlite3-dev
  libbenchmark-dev libgtest-dev libgmock-dev
  libcli11-dev help2man
)
if [[ "${1:-}" != "--test-only" ]]; then packages+=("${build_packages[@]}"); fi
if [[ "${1:-}" == "--test" || "${1:-}" == "--test-only" ]]; then
  # Test oracles: scikit-image for SSIM; Google Benchmark's compare.py (and
  # the scipy it needs) reads our --benchmark-out JSON.
  packages+=(python3-skimage python3-numpy libbenchmark-tools python3-scipy)
  # OpenImageIO's Python bindings: tools/recompute_metrics.py recomputes every
  # record's errors from the run's files (tests/e2e/test_recomputable_metrics.cpp).
  packages+=(python3-openimageio)
  # oiiotool reads the scaffold's EXR images back (tests/out_of_tree).
  packages+=(openimageio-tools)
  # Headless Chromium opens the HTML report (tests/report).
  packages+=(chromium)
  # pdflatex compiles `report --latex`'s tables and pgfplots figures, and
  # poppler renders and reads the PDFs (tests/report/test_latex_pdflatex.cpp):
  # booktabs is in texlive-latex-recommended, pgfplots in texlive-pictures.
  # 19 packages, 230 MB installed, 39 s with --no-install-recommends (2-core
  # VM while a build ran).
  packages+=(texlive-latex-base texlive-latex-recommended texlive-pictures poppler-utils)
  # The Debian package's test (tests/install): CPack's DEB generator with
  # dpkg-shlibdeps (dpkg-dev, file), readelf (binutils) and man for the page.
  packages+=(dpkg-dev file binutils man-db)
  # The Slurm job-array test (tests/slurm) starts a single-node Slurm.
  packages+=(slurm-wlm munge)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
# --force-unsafe-io: dpkg skips its fsync of every unpacked file (as Debian's
# own container images do). The 332 packages of a fresh install took 275 s
# instead of 405 s (debootstrapped Debian 12, 2-core VM under load);
# a machine that crashes mid-install is repaired by running this
# again.
"${sudo_cmd[@]}" apt-get install -o Dpkg::Options::=--force-unsafe-io -y -q --no-install-recommends "${missing[@]}"
