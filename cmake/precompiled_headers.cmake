# Precompiled third-party and standard headers, one set per target (the flags of lucent's targets differ, so a
# precompiled header is not shared between them). Only headers that lucent never configures with a macro of its
# own go here: stb (implementation macros) and the GL loaders' include order stay with the sources.
# Measured on the 2-core machine: docs/design.md, "Build and test time". LUCENT_PCH=OFF builds without them, which
# also checks that every source includes what it uses.
# Clang only by default: through a GCC 12 precompiled header, libstdc++'s inline code loses its system-header
# exemption from the middle end's warnings, and -Warray-bounds and -Wstringop-overflow report false positives in
# std::string (GCC bugs 105651 and 105329) that -Werror turns into errors; GCC's gain was also small (15-20% on the
# heaviest sources, whose time goes to optimization).
if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  set(lucent_pch_default ON)
else()
  set(lucent_pch_default OFF)
endif()
option(LUCENT_PCH "Precompile the heavy third-party headers of each target" ${lucent_pch_default})

set(LUCENT_PCH_STANDARD <algorithm> <array> <cmath> <cstdint> <filesystem> <fstream> <functional> <map> <memory>
    <optional> <span> <sstream> <string> <string_view> <vector>)

function(lucent_precompile_headers target)
  if(LUCENT_PCH)
    target_precompile_headers(${target} PRIVATE ${LUCENT_PCH_STANDARD} ${ARGN})
  endif()
endfunction()
