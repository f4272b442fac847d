# Warning, sanitizer and determinism flags shared by every xparam target.
add_library(xparam_compile_options INTERFACE)
target_compile_options(xparam_compile_options INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow=local -Wnon-virtual-dtor
  # OpenMesh and Eigen headers trip these; our own code is kept clean of them.
  -Wno-deprecated-copy -Wno-maybe-uninitialized
  # GCC 12 warns falsely on "literal" + std::string&& (GCC bug 105329).
  -Wno-restrict
  # Bit-identical results at any thread count need IEEE arithmetic without contraction.
  -ffp-contract=off)
if(XPARAM_WERROR)
  target_compile_options(xparam_compile_options INTERFACE -Werror)
endif()
if(XPARAM_SANITIZE)
  target_compile_options(xparam_compile_options INTERFACE
    -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(xparam_compile_options INTERFACE -fsanitize=address,undefined)
endif()
# OpenMesh's headers use M_PI and friends.
target_compile_definitions(xparam_compile_options INTERFACE _USE_MATH_DEFINES)
