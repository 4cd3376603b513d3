# Warning and sanitizer flags shared by every target of the project (never exported).
add_library(tumble_build_flags INTERFACE)
target_compile_options(tumble_build_flags INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  $<$<BOOL:${TUMBLE_WERROR}>:-Werror>)
# No fused multiply-adds behind the source's back: GCC contracts a*b+c by default wherever the
# target has FMA (aarch64, or x86-64 with -march=haswell and later), which changes trajectories
# between machines. A no-op on baseline x86-64. See docs/determinism.md.
target_compile_options(tumble_build_flags INTERFACE -ffp-contract=off)
if(TUMBLE_SANITIZE)
  target_compile_options(tumble_build_flags INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  target_link_options(tumble_build_flags INTERFACE -fsanitize=address,undefined)
endif()

# Adds the build flags to a target without making them part of its exported interface.
function(tumble_use_build_flags target)
  target_link_libraries(${target} PRIVATE $<BUILD_INTERFACE:tumble_build_flags>)
endfunction()
