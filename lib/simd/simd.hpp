#pragma once
// The four-wide versions (AVX2, where the processor has it) of the force loop, the integration
// (integrate/motion.cpp), the rebuild check (search/largest_move.cpp), the search's distance pre-test
// (search/linked_cells.cpp) and the fibres (forces/fibres.cpp): whether they run, and how they are
// marked. Each does per contact, particle, tie or segment the same operations in the same order as
// the plain loop it stands for, so both give
// the same bits (IEEE 754 rounds each operation alike in a vector lane and in a scalar register;
// no fused multiply-add is enabled, so none is contracted). Their operations are the layer's:
// lanes.hpp (lane types and arithmetic), lanes_avx2.hpp (what needs AVX2 instructions of its
// own), memory.hpp (loads, stores, gathers), layout.hpp (four vectors' layouts in registers).
// (AVX-512, eight lanes in one register, was tried for the law: slower on an Intel Xeon, same bits;
// eight as two AVX2 registers interleaved is faster: bench/results/design.md.)

namespace dem {

bool simd_loops_available();  // the processor has AVX2 (always false off x86-64)
bool simd_loops_on();         // available, and not turned off
void set_simd_loops(bool on); // on unless DEM_SIMD=off; tests turn it off to compare bit for bit

}  // namespace dem

#if defined(__x86_64__)
#define DEM_SIMD_LOOPS 1
// A four-wide loop: compiled for AVX2 (the build stays generic x86-64), called only where
// simd_loops_on(); the layer's operations inline only into such a function.
#define DEM_AVX2 [[gnu::target("avx2")]]
// An operation of the layer: always inlined into its four-wide caller (a 32-byte vector passed by
// value to a function of another target would change the calling convention).
#define DEM_AVX2_INLINE [[gnu::target("avx2"), gnu::always_inline]] inline
// A lambda inside a four-wide loop (a lambda does not take its enclosing function's target).
#define DEM_AVX2_LAMBDA __attribute__((target("avx2"), always_inline))
#endif
