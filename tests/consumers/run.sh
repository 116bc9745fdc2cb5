#!/usr/bin/env bash
# Builds and runs the two out-of-tree consumers (tests/consumers/cmake: find_package(roma);
# tests/consumers/pkgconfig: pkg-config) against an installed libroma.
#   run.sh install BUILD WORK   cmake --install BUILD into WORK/prefix, check what it
#                               installed, build and run both consumers against it
#   run.sh core SOURCE WORK     configure and build the core library alone, with the optional
#                               parts off and their packages hidden from CMake: it needs only
#                               Vulkan and glslang, and libroma.so links nothing else
#   run.sh deb BUILD WORK       cpack -G DEB in BUILD, check the packages' contents, install
#                               them with dpkg, build and run the pkg-config consumer against
#                               the system copy, remove the packages (root or sudo)
set -euo pipefail
mode=$1
build=$(realpath "$2")
work=$(realpath -m "$3")
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
mkdir -p "$work"

fail() { echo "consumers: $*" >&2; exit 1; }

build_cmake_consumer() { # $1: CMAKE_PREFIX_PATH (empty: the system)
  cmake -S "$here/cmake" -B "$work/cmake-consumer" -DCMAKE_BUILD_TYPE=Release ${1:+-DCMAKE_PREFIX_PATH="$1"} >/dev/null
  cmake --build "$work/cmake-consumer" >/dev/null
  "$work/cmake-consumer/consumer"
}
build_pkgconfig_consumer() {
  mkdir -p "$work/pkgconfig-consumer"
  make -s -C "$here/pkgconfig" O="$work/pkgconfig-consumer" >/dev/null
  "$work/pkgconfig-consumer/consumer"
}

case "$mode" in
core)
  src=$build
  cmake -S "$src" -B "$work" -DROMA_BUILD_REFERENCE=OFF -DROMA_BUILD_APPS=OFF -DROMA_BUILD_TESTS=OFF \
        -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON -DCMAKE_DISABLE_FIND_PACKAGE_embree=ON \
        -DCMAKE_DISABLE_FIND_PACKAGE_Doxygen=ON -DCMAKE_DISABLE_FIND_PACKAGE_glfw3=ON >"$work.log" 2>&1 \
    || { cat "$work.log" >&2; fail "the core-only configure failed"; }
  cmake --build "$work" -j "$(nproc)" --target roma roma_tools >>"$work.log" 2>&1 \
    || { tail -30 "$work.log" >&2; fail "the core-only build failed"; }
  needed=$(readelf -d "$work/src/libroma.so" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | sort | tr '\n' ' ')
  echo "== core-only build: libroma.so needs $needed"
  for lib in $needed; do
    case "$lib" in
      libvulkan.so.1|libm.so.6|libc.so.6) ;;
      *) fail "the core library links $lib" ;;
    esac
  done
  ;;
install)
  prefix="$work/prefix"
  cmake --install "$build" --prefix "$prefix" >/dev/null
  for f in include/roma/roma.h include/roma/api.h include/roma/trace.glsl include/roma/trace_descriptors.glsl \
           include/roma/trace_types.h include/roma/ray_start.glsl lib/libroma.so lib/cmake/roma/romaConfig.cmake \
           lib/cmake/roma/romaConfigVersion.cmake lib/pkgconfig/roma.pc bin/roma-render bin/roma-viewer; do
    [ -e "$prefix/$f" ] || fail "cmake --install did not install $f"
  done
  [ -n "$(ls "$prefix"/lib/libroma.so.0.* 2>/dev/null)" ] || fail "no versioned libroma.so.0.*"
  # Nothing internal is installed.
  if find "$prefix/include" -name '*internal*' | grep -q .; then fail "internal headers installed"; fi
  "$prefix/bin/roma-viewer" --headless --frames 2 --size 32x32 --screenshot "$work/viewer.png" >/dev/null \
    || fail "the installed roma-viewer does not run from $prefix (RPATH?)"
  echo "== find_package(roma) consumer against $prefix"
  build_cmake_consumer "$prefix"
  echo "== pkg-config consumer against $prefix"
  PKG_CONFIG_PATH="$prefix/lib/pkgconfig" build_pkgconfig_consumer
  ;;
deb)
  run=()
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || fail "installing the packages needs root or sudo"
    run=(sudo)
  fi
  (cd "$build" && cpack -G DEB -B "$work/packages" >"$work/cpack.log" 2>&1) || { cat "$work/cpack.log" >&2; fail "cpack failed"; }
  shopt -s nullglob
  debs=("$work"/packages/*.deb)
  [ ${#debs[@]} -eq 3 ] || fail "expected 3 packages, cpack made: ${debs[*]##*/}"
  for deb in "${debs[@]}"; do
    name=$(dpkg-deb -f "$deb" Package)
    echo "== $name $(dpkg-deb -f "$deb" Version): depends on $(dpkg-deb -f "$deb" Depends)"
    dpkg-deb -c "$deb" | awk '{print $6}' >"$work/$name.files"
  done
  grep -q '^./usr/lib/libroma.so.0.1.0$' "$work/libroma0.files" || fail "libroma0 lacks libroma.so.0.1.0"
  grep -q '^./usr/include/roma/trace.glsl$' "$work/libroma-dev.files" || fail "libroma-dev lacks trace.glsl"
  grep -q '^./usr/lib/cmake/roma/romaConfig.cmake$' "$work/libroma-dev.files" || fail "libroma-dev lacks romaConfig.cmake"
  grep -q '^./usr/lib/pkgconfig/roma.pc$' "$work/libroma-dev.files" || fail "libroma-dev lacks roma.pc"
  grep -q '^./usr/bin/roma-render$' "$work/roma-tools.files" || fail "roma-tools lacks roma-render"
  grep -q '^./usr/bin/roma-viewer$' "$work/roma-tools.files" || fail "roma-tools lacks roma-viewer"
  if grep -q 'include' "$work/libroma0.files"; then fail "libroma0 carries headers"; fi
  if dpkg-query -W -f='${Status}' libroma0 2>/dev/null | grep -q "install ok installed"; then
    fail "libroma0 is already installed on this machine"
  fi
  trap '"${run[@]}" dpkg -P roma-tools libroma-dev libroma0 >/dev/null 2>&1 || true' EXIT
  "${run[@]}" dpkg -i "${debs[@]}" >/dev/null
  echo "== pkg-config consumer against the installed packages"
  build_pkgconfig_consumer
  echo "== find_package(roma) consumer against the installed packages"
  build_cmake_consumer ""
  roma-render --size 16x16 --spp 1 --quiet --out "$work/render" >/dev/null
  [ -f "$work/render/ao.pfm" ] || fail "the installed roma-render wrote no ao.pfm"
  roma-viewer --headless --frames 2 --size 32x32 --screenshot "$work/viewer.png" >/dev/null
  [ -f "$work/viewer.png" ] || fail "the installed roma-viewer wrote no picture"
  "${run[@]}" dpkg -P roma-tools libroma-dev libroma0 >/dev/null
  trap - EXIT
  ! dpkg-query -W -f='${Status}' libroma0 2>/dev/null | grep -q "install ok installed" || fail "libroma0 still installed"
  echo "packages installed, used and removed"
  ;;
*)
  fail "usage: run.sh install|deb BUILD WORK"
  ;;
esac
