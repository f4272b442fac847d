# Warning, sanitizer and determinism flags shared by every xparam target.
add_library(xparam_compile_options INTERFACE)
target_compile_options(xparam_compile_options INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow=local -Wnon-virtual-dtor
  # OpenMesh and Eigen headers trip these; our own code is kept clean of them.
  -Wno-deprecated-copy -Wno-maybe-uninitialized
  # GCC 12 warns falsely on "literal" + std::string&& (GCC bug 105329); with the standard headers
  # precompiled (cmake/XparamStage.cmake) it inlines differently and the same false positive comes
  # out of libstdc++ as array-bounds and stringop-overflow too. AddressSanitizer checks bounds.
  -Wno-restrict -Wno-array-bounds -Wno-stringop-overflow
  # Bit-identical results at any thread count need IEEE arithmetic without contraction.
  -ffp-contract=off)
if(XPARAM_WERROR)
  target_compile_options(xparam_compile_options INTERFACE -Werror)
endif()
if(XPARAM_SANITIZE)
  # UBSan's pointer checks are left to AddressSanitizer, which reports null and out-of-bounds
  # accesses itself: on Eigen-heavy files they more than double the compile time (measured on
  # param/patch_parameterization.cpp at -O1: 53 s of CPU with them, 21 s without, 24 s with
  # AddressSanitizer alone). The checks kept are those of arithmetic, shifts, conversions,
  # bool/enum values, unreachable code and missing returns.
  target_compile_options(xparam_compile_options INTERFACE
    -fsanitize=address,undefined -fno-sanitize=pointer-overflow,alignment,null,object-size,vptr
    -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(xparam_compile_options INTERFACE -fsanitize=address,undefined)
endif()
# OpenMesh's headers use M_PI and friends.
target_compile_definitions(xparam_compile_options INTERFACE _USE_MATH_DEFINES)
