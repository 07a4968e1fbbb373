#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Install what this machine lacks, then build and install the Python package into .venv.
# Used by scripts/study.sh (`setup.sh study`: what the study needs), scripts/test.sh and
# scripts/bench.sh (`setup.sh test`: everything). Safe to run again: it skips what is done.
#   Debian packages: compilers, CMake, Ninja, Eigen 3.4, SuiteSparse, toml++, CLI11, Catch2 v2, Google Benchmark,
#   ccache (compiles are cached in ~/.cache/ccache, keyed on paths relative to the clone: a second clone
#   or a rebuild after a small change compiles only what changed).
#   PyPI (into .venv): numpy, matplotlib, pybind11, scikit-build-core; for tests also scipy, pytest (with
#   pytest-xdist: the tests run on both cores), sympy, ezdxf,
#   hypothesis, the studies' extras (pandas, pyarrow, tqdm, dask[distributed]), Sphinx with MyST (the docs site),
#   ruff (with Debian's clang-format: the style test), and the design page's Dash with Selenium (driving
#   Debian's chromium and chromium-driver in its browser test).
set -euo pipefail
cd "$(dirname "$0")/.."
mode=${1:-test}
case "$mode" in
  study | test | compilers) ;;
  *) echo "setup: unknown mode '$mode' (study, test or compilers)" >&2; exit 2 ;;
esac

# `setup.sh compilers`: the Debian packages the C++ build needs, and nothing else (scripts/test.sh starts
# the sanitized build on them while the rest is fetched).
apt_packages=(build-essential cmake ninja-build libeigen3-dev libsuitesparse-dev libspectra-dev libtomlplusplus-dev libcli11-dev catch2 libbenchmark-dev
              ccache)
[ "$mode" = compilers ] || apt_packages+=(python3 python3-dev python3-venv)
[ "$mode" != test ] || apt_packages+=(clang-format)  # the style test (tests/python/test_style.py)
[ "$mode" != test ] || apt_packages+=(chromium chromium-driver)  # the design page's browser test
missing=()
for p in "${apt_packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing Debian packages: ${missing[*]}"
  sudo=""; [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi

[ "$mode" != compilers ] || exit 0

# ccache: paths relative to the clone, so another clone of the same sources hits the same entries.
export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1

python=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  echo "setup: creating .venv with $($python --version)"
  $python -m venv .venv
fi
export PIP_DISABLE_PIP_VERSION_CHECK=1
need() {  # need MODULE... : pip-install the given packages unless all modules import
  local modules=$1; shift
  if ! .venv/bin/python -c "import $modules" 2>/dev/null; then
    echo "setup: installing Python packages into .venv: $*"
    .venv/bin/python -m pip install -q "$@"
  fi
}
need "numpy, matplotlib, pybind11, scikit_build_core" numpy matplotlib "pybind11>=2.12" "scikit-build-core>=0.10"
[ "$mode" = study ] || need "scipy, pytest, xdist, sympy, ezdxf, hypothesis" scipy pytest pytest-xdist sympy ezdxf hypothesis
[ "$mode" = study ] || need "pandas, pyarrow, tqdm, distributed" pandas pyarrow tqdm "dask[distributed]"
[ "$mode" = study ] || need "sphinx, myst_parser" sphinx myst-parser
[ "$mode" = study ] || need "ruff" "ruff==0.17.6"  # the version .pre-commit-config.yaml pins
[ "$mode" = study ] || need "dash, selenium" dash selenium  # the design page and its browser test

# Rebuild the package only when its sources changed.
stamp=$(cat pyproject.toml CMakeLists.txt cmake/* $(find include python src -type f \( -name '*.hpp' -o -name '*.cpp' -o -name '*.py' -o -name '*.txt' -o -name '*.pyi' \) | sort) | sha256sum | cut -c1-16)
# The build folder is kept (build/python), so a rebuild compiles only what changed; flock keeps two
# set-ups in one clone from building at once.
if [ "$(cat .venv/.camfollower-stamp 2>/dev/null)" != "$stamp" ]; then
  echo "setup: building and installing the camfollower Python package (about 4 min the first time on 2 cores)"
  flock .venv/.camfollower-build .venv/bin/python -m pip install -q --no-build-isolation --no-deps \
    -Cbuild-dir=build/python -Ccmake.define.CMAKE_CXX_COMPILER_LAUNCHER="$(command -v ccache || true)" .
  echo "$stamp" > .venv/.camfollower-stamp
fi
