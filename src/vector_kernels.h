#pragma once
// Loops over contiguous doubles that the compiler turns into vector
// instructions, shared by the force batches and the integrators.
//
// PARTICLES_VECTOR_CLONES before a kernel builds it three times on x86-64
// with GCC: for the base instruction set (SSE2), for AVX2 and for AVX-512
// (x86-64-v4), the one to run chosen by the processor when the program loads
// (function multiversioning: the default build stays portable). The library
// is compiled with -ffp-contract=off, so every clone rounds each operation
// alike (no fused multiply-add) and gives the same bits. Square roots and
// divisions bound the spring loops: 8 lanes of AVX-512 took 1.0 ns a spring
// on the development machine, 4 of AVX2 1.9 ns.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
#define PARTICLES_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "avx2", "default")))
#else
#define PARTICLES_VECTOR_CLONES
#endif

namespace particles {

// to[u] += from[u] and to[u] −= from[u], u < count (vector_kernels.cpp).
void addTerms(int count, const double* from, double* to);
void subtractTerms(int count, const double* from, double* to);

}  // namespace particles
