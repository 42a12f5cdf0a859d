#!/usr/bin/env bash
# outside_project.sh BUILD_DIR SOURCE_DIR [PYTHON_MODULE_DIR]: lucent as another program sees it once installed.
#   1. `cmake --install` into a temporary prefix;
#   2. examples/ built as an outside CMake project with find_package(lucent), run from another folder;
#   3. the same program built with pkg-config alone (c++ $(pkg-config --cflags --libs lucent epoxy));
#   4. both render the default scene to PNGs identical to the in-tree build's;
#   5. the installed `lucent` command renders the default scene; the example scenes are installed;
#   6. the installed Python module imports in a clean environment (env -i, nothing of the build tree on any path),
#      from the folder Debian's Python searches under the prefix (PYTHON_MODULE_DIR, relative to the prefix).
# Exits non-zero, naming the step, on the first difference.
set -euo pipefail
build=$(cd "$1" && pwd)
source=$(cd "$2" && pwd)
python_dir=${3:-}
work=$(mktemp -d "${TMPDIR:-/tmp}/lucent-install.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "outside_project.sh: $*" >&2; exit 1; }

prefix="$work/prefix"
cmake --install "$build" --prefix "$prefix" > "$work/install.log" || { cat "$work/install.log"; fail "cmake --install failed"; }
library=$(find "$prefix" -name 'liblucent.so' -print -quit)
[ -n "$library" ] || fail "no liblucent.so under $prefix"
libdir=$(dirname "$library")
[ -f "$prefix/include/lucent/lucent.h" ] || fail "no include/lucent/lucent.h under $prefix"

# The in-tree program: what the installed library must reproduce.
"$build/examples/embed_renderer" - "$work/in_tree.png" > /dev/null

# find_package(lucent CONFIG), from another folder, with nothing of the build tree on the search paths.
generator=()
command -v ninja > /dev/null && generator=(-G Ninja)
cmake -S "$source/examples" -B "$work/find_package" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$prefix" > "$work/configure.log" 2>&1 || { cat "$work/configure.log"; fail "configure against the install failed"; }
cmake --build "$work/find_package" > "$work/build.log" 2>&1 || { cat "$work/build.log"; fail "build against the install failed"; }
(cd "$work" && ./find_package/embed_renderer - "$work/find_package.png" > /dev/null) || fail "the find_package build did not run"
ldd "$work/find_package/embed_renderer" > "$work/ldd.txt"
grep -q "$libdir/liblucent.so" "$work/ldd.txt" || fail "the find_package build does not load the installed liblucent.so"
cmp -s "$work/in_tree.png" "$work/find_package.png" || fail "the find_package build's image differs from the in-tree build's"

# pkg-config alone.
export PKG_CONFIG_PATH="$libdir/pkgconfig"
flags=$(pkg-config --cflags --libs lucent epoxy) || fail "pkg-config does not find lucent"
# shellcheck disable=SC2086
c++ -std=c++20 -O1 "$source/examples/embed_renderer.cpp" -o "$work/pkg_config_renderer" $flags -Wl,-rpath,"$libdir" \
  || fail "the pkg-config build failed"
(cd "$work" && ./pkg_config_renderer - "$work/pkg_config.png" > /dev/null) || fail "the pkg-config build did not run"
cmp -s "$work/in_tree.png" "$work/pkg_config.png" || fail "the pkg-config build's image differs from the in-tree build's"

# The installed command.
(cd "$work" && "$prefix/bin/lucent" render --set render.width=64 --set render.height=40 --set render.frames=1 \
   -o "$work/cli.png" > /dev/null) || fail "the installed lucent render failed"
[ -s "$work/cli.png" ] || fail "the installed lucent render wrote no image"

# The Python module, in a clean environment.
if [ -n "$python_dir" ]; then
  module_dir="$prefix/$python_dir"
  [ -d "$module_dir" ] || fail "no $python_dir under the prefix"
  (cd "$work" && env -i HOME="$work" PATH=/usr/bin:/bin PYTHONPATH="$module_dir" PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 -c "
import lucent, sys
assert lucent.__file__.startswith('$module_dir'), lucent.__file__
image = lucent.render(lucent.load_scene(), width=32, height=20, frames=1)
assert image.shape == (20, 32, 3) and image.mean() > 0, image.mean()
lucent.load_scene('$prefix/share/lucent/scenes/marble_textured.json')  # an installed scene with its maps
") || fail "the installed Python module does not import and render"
  # Installed under /usr (the Debian package's prefix; DESTDIR keeps it in the temporary folder), the module goes to
  # Debian's packaged modules, on its Python's own path.
  DESTDIR="$work/destdir" cmake --install "$build" --prefix /usr/ > "$work/install-usr.log" \
    || { cat "$work/install-usr.log"; fail "cmake --install --prefix /usr failed"; }
  if [ "$python_dir" != "lib/python3/dist-packages" ] && /usr/bin/python3 -c "import sysconfig, sys; sys.exit(sysconfig.get_default_scheme() != 'posix_local')"; then
    ls "$work/destdir/usr/lib/python3/dist-packages/"lucent*.so > /dev/null 2>&1 \
      || fail "installed under /usr, the Python module is not in lib/python3/dist-packages"
  fi
  # Installed under /usr/local, the same folder is on Debian's Python's own path: no PYTHONPATH needed.
  if [ "$python_dir" != "lib/python3/dist-packages" ]; then
    env -i PATH=/usr/bin:/bin /usr/bin/python3 -c "import sys; sys.exit(0 if '/usr/local/$python_dir' in sys.path else 1)" \
      || fail "/usr/local/$python_dir is not on /usr/bin/python3's path"
  fi
fi
echo "outside_project.sh: installed lucent builds, links and renders as the in-tree build does"
