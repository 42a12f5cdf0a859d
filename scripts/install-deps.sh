#!/usr/bin/env bash
# Installs every Debian 12 package that lucent's build, tests and examples need.
# Idempotent: packages already present are skipped; run as root (or through sudo).
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config git
  # compiler cache (cmake/compiler_cache.cmake): a rebuild of unchanged sources, in any clone, is a cache lookup
  ccache
  # fuzzing (scripts/fuzz.sh): clang and its libFuzzer runtime (libclang-rt-14-dev is only recommended by clang)
  clang libclang-rt-14-dev
  # OpenGL 4.5 through EGL (surfaceless) and GLFW; Mesa llvmpipe for machines without a GPU
  libepoxy-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libglfw3-dev
  # maths, scenes, images, command line, tests
  libglm-dev libassimp-dev libopenexr-dev libstb-dev nlohmann-json3-dev libcli11-dev libfmt-dev
  # glTF materials, textures, cameras and lights in and out (src/scene/gltf_*.cpp)
  libtinygltf-dev
  libgtest-dev libgmock-dev
  # CPU ground truth (reference renderers)
  libembree-dev libtbb-dev
  # vdb medium fields (src/media/medium_vdb.cpp; FindOpenVDB also needs Boost.Iostreams' headers) and the example
  # VDB's generator (scripts/make_plume_vdb.py, Debian's /usr/bin/python3 with pyopenvdb)
  libopenvdb-dev libboost-iostreams-dev python3-openvdb
  # local-global's isotropic remeshing (src/methods/local_global/remesh_cgal.cpp): CGAL 5.5, header-only with GMP and MPFR
  libcgal-dev
  # viewer
  libimgui-dev xvfb xauth
  # example assets: the Stanford bunny at /usr/share/glmark2/models/bunny.obj
  glmark2-data
  # references rendered in batches (docs/references.md: GNU parallel, tested locally)
  parallel
  # benchmark plots
  gnuplot-nox
  # the Python module (python/) and its tests; Debian's /usr/bin/python3
  pybind11-dev python3-dev python3-numpy python3-pytest
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
