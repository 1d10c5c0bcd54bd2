/* Throughput of the operations the force loops are made of, on this CPU: the core clock (a chain
 * of dependent scalar adds, 4 cycles each on the Intel and AMD cores pdk runs on), the square root
 * and the division (vsqrtpd, vdivpd) at 256 and 512 bits, the reciprocal square-root estimate
 * (vrsqrt14pd), FMA, and the gather (vgatherdpd) from an L1-resident table; the clock while
 * 512-bit FMAs run; whether the divide unit overlaps FMA work; then the correctly rounded square
 * root and reciprocal built from the estimates with FMA steps (below), their cost, and a check
 * that they equal vsqrtpd / vdivpd bit for bit on random and edge-case inputs. Those two are an
 * experiment, not library code: on the Intel host they cost as much as the instructions and
 * slowed the kernels (bench/log.md, "Where the cycles go on an Intel Xeon").
 *
 *   bench_ops [--reps N] [--check N]
 *
 * Printed per operation: ns per vector instruction (median of 5 runs), cycles per instruction at
 * the measured clock, and cycles per double. The in-core bound of a loop follows from its counts
 * per bond (bench/README.md, "Where the cycles go").
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

#include "kernels.h"

PDK_KERNEL_FP_EXACT

#pragma GCC target("avx512f,avx512vl,avx512dq,avx512bw,avx2,fma")

/* Correctly rounded square root and reciprocal of 8 doubles from the AVX-512 estimates
 * (vrsqrt14pd, vrcp14pd, relative error < 2^-14) and FMA steps: the same bits as vsqrtpd and
 * vdivpd (1 / b) in round-to-nearest, without the divide unit, whose throughput bounds the
 * PMB and LPS loops on the Intel host (bench/log.md, "Where the cycles go on an Intel Xeon").
 *
 * Method. Newton steps take the estimate to a candidate within about half an ulp; the candidate is
 * then checked against the exact residual and moved by one ulp when it is not the correctly
 * rounded result:
 *   square root: s candidate for sqrt(a), e = a - s^2 (one FMA; exact when s is within an ulp:
 *     e is a multiple of ulp(s)^2 below 2^53 ulp(s)^2, and larger residuals only need their sign
 *     and size, which rounding keeps). The midpoint above s is s + u/2 (u = s+ - s), so
 *     sqrt(a) > s + u/2  <=>  a > s^2 + s u + u^2/4  <=>  e > s u  (e and s u are multiples of
 *     u^2; u^2/4 is below the step). Below: sqrt(a) < s - u-/2  <=>  e <= -s u- (u- = s - s-,
 *     u/2 at a power of two; the same argument, and at a power of two a - s^2 is a multiple of
 *     s u-). Ties cannot occur (the square of a midpoint has more than 53 significant bits).
 *   reciprocal: y candidate for 1/b, e = 1 - b y (exact by the same argument); 1/b > y + u/2
 *     <=> 2e > b u, 1/b < y - u-/2 <=> 2e < -b u- (ties impossible: 1/b is a midpoint only if b
 *     is the reciprocal of a 54-bit number, which is not a double).
 * Both need the candidate within 1.5 ulp of the exact value (the Newton steps give about 0.5;
 * check() below compares the bits with vsqrtpd / vdivpd), and operands in
 * [2^-960, 2^960], where no product above overflows or loses bits to underflow. A vector with any
 * lane outside (zero, a subnormal, inf, NaN, negative) is handed to vsqrtpd / vdivpd whole, so
 * every input gives the instruction's result.
 *
 * Cost per 8 doubles: square root 24 instructions, reciprocal 20 (the table this program prints
 * gives their time beside vsqrtpd and vdivpd). The steps use FMA on purpose (intrinsics, which
 * PDK_KERNEL_FP_EXACT does not touch); the results are exact regardless. */
#define EX_INLINE static inline __attribute__((always_inline))

/* The functions are written once per width: ex_sqrt8, ex_rcp8 on zmm, ex_sqrt4, ex_rcp4 on ymm
 * (AVX-512 VL). */
#define EX_DEFINE(W, VD, PFX, FULL, TO_PD, TO_SI, SET1I)                                           \
  /* Lanes with a in [2^-960, 2^960] (NaN fails both comparisons). */                              \
  EX_INLINE __mmask8 ex_in_range##W(VD a) {                                                        \
    return PFX##_cmp_pd_mask(a, PFX##_set1_pd(0x1p-960), _CMP_GE_OQ) &                             \
           PFX##_cmp_pd_mask(a, PFX##_set1_pd(0x1p960), _CMP_LE_OQ);                               \
  }                                                                                                \
  /* the next double up and down (positive normal x) */                                            \
  EX_INLINE VD ex_next_up##W(VD x) { return TO_PD(PFX##_add_epi64(TO_SI(x), SET1I(1))); }          \
  EX_INLINE VD ex_next_down##W(VD x) { return TO_PD(PFX##_sub_epi64(TO_SI(x), SET1I(1))); }        \
  /* sqrt(a), correctly rounded (the bits of vsqrtpd) */                                           \
  EX_INLINE VD ex_sqrt##W(VD a) {                                                                  \
    if (__builtin_expect(ex_in_range##W(a) != FULL, 0)) return PFX##_sqrt_pd(a);                   \
    const VD half = PFX##_set1_pd(0.5);                                                            \
    const VD y = PFX##_rsqrt14_pd(a);                                                              \
    VD s = PFX##_mul_pd(a, y), h = PFX##_mul_pd(half, y); /* s ~ sqrt(a), h ~ 1/(2 s) */           \
    VD r = PFX##_fnmadd_pd(s, h, half);                   /* 2^-14 -> 2^-28 */                     \
    s = PFX##_fmadd_pd(s, r, s);                                                                   \
    h = PFX##_fmadd_pd(h, r, h);                                                                   \
    r = PFX##_fnmadd_pd(s, h, half); /* -> 2^-53 and rounding */                                   \
    s = PFX##_fmadd_pd(s, r, s);                                                                   \
    VD e = PFX##_fnmadd_pd(s, s, a); /* one correction step: s within about half an ulp */         \
    s = PFX##_fmadd_pd(e, h, s);                                                                   \
    e = PFX##_fnmadd_pd(s, s, a); /* exact residual a - s^2 */                                     \
    const VD sp = ex_next_up##W(s), sm = ex_next_down##W(s);                                       \
    const __mmask8 up = PFX##_cmp_pd_mask(e, PFX##_mul_pd(s, PFX##_sub_pd(sp, s)), _CMP_GT_OQ);    \
    const __mmask8 dn = PFX##_cmp_pd_mask(e, PFX##_mul_pd(s, PFX##_sub_pd(sm, s)), _CMP_LE_OQ);    \
    s = PFX##_mask_mov_pd(s, up, sp);                                                              \
    return PFX##_mask_mov_pd(s, dn, sm);                                                           \
  }                                                                                                \
  /* 1 / b, correctly rounded (the bits of vdivpd 1, b) */                                         \
  EX_INLINE VD ex_rcp##W(VD b) {                                                                   \
    const VD one = PFX##_set1_pd(1.0);                                                             \
    if (__builtin_expect(ex_in_range##W(b) != FULL, 0)) return PFX##_div_pd(one, b);               \
    VD y = PFX##_rcp14_pd(b);                                                                      \
    VD e = PFX##_fnmadd_pd(b, y, one); /* 2^-14 -> 2^-42: y (1 + e + e^2) */                       \
    e = PFX##_fmadd_pd(e, e, e);                                                                   \
    y = PFX##_fmadd_pd(y, e, y);                                                                   \
    e = PFX##_fnmadd_pd(b, y, one); /* -> 2^-53 and rounding */                                    \
    y = PFX##_fmadd_pd(y, e, y);                                                                   \
    e = PFX##_fnmadd_pd(b, y, one); /* exact residual 1 - b y */                                   \
    e = PFX##_add_pd(e, e);                                                                        \
    const VD yp = ex_next_up##W(y), ym = ex_next_down##W(y);                                       \
    const __mmask8 up = PFX##_cmp_pd_mask(e, PFX##_mul_pd(b, PFX##_sub_pd(yp, y)), _CMP_GT_OQ);    \
    const __mmask8 dn = PFX##_cmp_pd_mask(e, PFX##_mul_pd(b, PFX##_sub_pd(ym, y)), _CMP_LT_OQ);    \
    y = PFX##_mask_mov_pd(y, up, yp);                                                              \
    return PFX##_mask_mov_pd(y, dn, ym);                                                           \
  }

EX_DEFINE(8, __m512d, _mm512, 0xff, _mm512_castsi512_pd, _mm512_castpd_si512, _mm512_set1_epi64)
EX_DEFINE(4, __m256d, _mm256, 0x0f, _mm256_castsi256_pd, _mm256_castpd_si256, _mm256_set1_epi64x)

#define BS_INLINE_FMA static inline __attribute__((always_inline))
#define N 1024 /* 8 KiB of doubles: L1 */

static double now(void) {
  struct timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t); /* CPU time: other jobs' turns do not count */
  return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double in[N] __attribute__((aligned(64)));
static int32_t idx[N] __attribute__((aligned(64)));
static volatile double sink;
static long reps = 20000;

/* ns per add of a dependent chain: the clock is 4 / that (latency of addsd). */
static double t_chain(void) {
  double x = 1.0, y = 1e-17;
  const double t0 = now();
  for (long r = 0; r < reps * 64; ++r) {
    __asm__ volatile("addsd %1, %0\n\taddsd %1, %0\n\taddsd %1, %0\n\taddsd %1, %0"
                     : "+x"(x)
                     : "x"(y));
  }
  const double t = now() - t0;
  sink = x;
  return t / ((double)reps * 64 * 4);
}

/* Each body processes N doubles (N / width instructions) and sums the results into 4
 * accumulators; the time per instruction is the total over (reps * N / width). */
#define BODY512(name, expr)                                                                        \
  static double name(void) {                                                                       \
    __m512d s0 = _mm512_setzero_pd(), s1 = s0, s2 = s0, s3 = s0;                                   \
    const __m512d one = _mm512_set1_pd(1.0);                                                       \
    (void)one;                                                                                     \
    const double t0 = now();                                                                       \
    for (long r = 0; r < reps; ++r)                                                                \
      for (int k = 0; k < N; k += 32) {                                                            \
        __m512d a;                                                                                 \
        a = _mm512_load_pd(in + k);                                                                \
        s0 = _mm512_add_pd(s0, (expr));                                                            \
        a = _mm512_load_pd(in + k + 8);                                                            \
        s1 = _mm512_add_pd(s1, (expr));                                                            \
        a = _mm512_load_pd(in + k + 16);                                                           \
        s2 = _mm512_add_pd(s2, (expr));                                                            \
        a = _mm512_load_pd(in + k + 24);                                                           \
        s3 = _mm512_add_pd(s3, (expr));                                                            \
        (void)a;                                                                                   \
      }                                                                                            \
    const double t = now() - t0;                                                                   \
    double o[8];                                                                                   \
    _mm512_storeu_pd(o, _mm512_add_pd(_mm512_add_pd(s0, s1), _mm512_add_pd(s2, s3)));              \
    sink = o[0];                                                                                   \
    return t / ((double)reps * N / 8);                                                             \
  }
#define BODY256(name, expr)                                                                        \
  static double name(void) {                                                                       \
    __m256d s0 = _mm256_setzero_pd(), s1 = s0, s2 = s0, s3 = s0;                                   \
    const __m256d one = _mm256_set1_pd(1.0);                                                       \
    (void)one;                                                                                     \
    const double t0 = now();                                                                       \
    for (long r = 0; r < reps; ++r)                                                                \
      for (int k = 0; k < N; k += 16) {                                                            \
        __m256d a;                                                                                 \
        a = _mm256_load_pd(in + k);                                                                \
        s0 = _mm256_add_pd(s0, (expr));                                                            \
        a = _mm256_load_pd(in + k + 4);                                                            \
        s1 = _mm256_add_pd(s1, (expr));                                                            \
        a = _mm256_load_pd(in + k + 8);                                                            \
        s2 = _mm256_add_pd(s2, (expr));                                                            \
        a = _mm256_load_pd(in + k + 12);                                                           \
        s3 = _mm256_add_pd(s3, (expr));                                                            \
        (void)a;                                                                                   \
      }                                                                                            \
    const double t = now() - t0;                                                                   \
    double o[4];                                                                                   \
    _mm256_storeu_pd(o, _mm256_add_pd(_mm256_add_pd(s0, s1), _mm256_add_pd(s2, s3)));              \
    sink = o[0];                                                                                   \
    return t / ((double)reps * N / 4);                                                             \
  }

BODY512(t_load512, a)
BODY512(t_sqrt512, _mm512_sqrt_pd(a))
BODY512(t_div512, _mm512_div_pd(one, a))
BODY512(t_rsqrt14_512, _mm512_rsqrt14_pd(a))
BODY512(t_exsqrt512, ex_sqrt8(a))
BODY512(t_exrcp512, ex_rcp8(a))
BODY512(t_gather512,
        _mm512_i32gather_pd(_mm256_load_si256((const __m256i *)(const void *)(idx + (k & (N - 8)))),
                            in, 8))
BODY256(t_load256, a)
BODY512(t_mix2sqrt, _mm512_add_pd(_mm512_sqrt_pd(a), _mm512_sqrt_pd(_mm512_add_pd(a, one))))
BODY512(t_mixsqrt, _mm512_add_pd(_mm512_sqrt_pd(a), ex_sqrt8(_mm512_add_pd(a, one))))
BODY512(t_mix2ex, _mm512_add_pd(ex_sqrt8(a), ex_sqrt8(_mm512_add_pd(a, one))))
BODY256(t_exsqrt256, ex_sqrt4(a))
BODY256(t_exrcp256, ex_rcp4(a))
BODY256(t_sqrt256, _mm256_sqrt_pd(a))
BODY256(t_div256, _mm256_div_pd(one, a))
BODY256(t_gather256,
        _mm256_i32gather_pd(in,
                            _mm_load_si128((const __m128i *)(const void *)(idx + (k & (N - 4)))),
                            8))

/* 8 independent FMA chains (latency 4): the FMA units' throughput, not the harness's adds */
#define FMA_CHAINS(name, T, set1, fma, store)                                                      \
  static double name(void) {                                                                       \
    T c[8];                                                                                        \
    for (int l = 0; l < 8; ++l)                                                                    \
      c[l] = set1(1.0 + l);                                                                        \
    const T m = set1(0.999999), p = set1(1e-7);                                                    \
    const double t0 = now();                                                                       \
    for (long r = 0; r < reps * 64; ++r)                                                           \
      for (int l = 0; l < 8; ++l)                                                                  \
        c[l] = fma(c[l], m, p);                                                                    \
    const double t = now() - t0;                                                                   \
    double o[8];                                                                                   \
    store(o, c[0] + c[7]);                                                                         \
    sink = o[0];                                                                                   \
    return t / ((double)reps * 64 * 8);                                                            \
  }
FMA_CHAINS(t_fmachain512, __m512d, _mm512_set1_pd, _mm512_fmadd_pd, _mm512_storeu_pd)
FMA_CHAINS(t_fmachain256, __m256d, _mm256_set1_pd, _mm256_fmadd_pd, _mm256_storeu_pd)

/* The clock while the vector units run FMAs: 4 dependent scalar adds (16 cycles) beside 16
 * independent FMAs per iteration (8 cycles on two units), so the add chain sets the pace and its
 * time gives the clock under that load (AVX-512 frequency licence). */
#define CLOCK_UNDER(name, T, set1, fma)                                                            \
  static double name(void) {                                                                       \
    T c[16];                                                                                       \
    for (int l = 0; l < 16; ++l)                                                                   \
      c[l] = set1(1.0 + l);                                                                        \
    const T m = set1(0.999999), p = set1(1e-7);                                                    \
    double x = 1.0, y = 1e-17;                                                                     \
    const double t0 = now();                                                                       \
    for (long r = 0; r < reps * 16; ++r) {                                                         \
      __asm__ volatile("addsd %1, %0\n\taddsd %1, %0\n\taddsd %1, %0\n\taddsd %1, %0"              \
                       : "+x"(x)                                                                   \
                       : "x"(y));                                                                  \
      for (int l = 0; l < 16; ++l)                                                                 \
        c[l] = fma(c[l], m, p);                                                                    \
    }                                                                                              \
    const double t = now() - t0;                                                                   \
    double o[8];                                                                                   \
    memcpy(o, &c[3], sizeof(double));                                                              \
    sink = o[0] + x;                                                                               \
    return t / ((double)reps * 16 * 4);                                                            \
  }
CLOCK_UNDER(t_clock512, __m512d, _mm512_set1_pd, _mm512_fmadd_pd)
CLOCK_UNDER(t_clock256, __m256d, _mm256_set1_pd, _mm256_fmadd_pd)

/* 24 independent FMAs (a 512-bit vector's worth of bond arithmetic, ~45 instructions per 8 bonds
 * in the PMB loops), alone and beside one vsqrtpd: whether the divide unit overlaps the FMA ports.
 */
BS_INLINE_FMA __m512d fma_work(__m512d a) {
  const __m512d m = _mm512_set1_pd(0.999), p = _mm512_set1_pd(1e-3);
  __m512d c0 = a, c1 = _mm512_add_pd(a, p), c2 = _mm512_mul_pd(a, m);
  for (int k = 0; k < 8; ++k) {
    c0 = _mm512_fmadd_pd(c0, m, p);
    c1 = _mm512_fmadd_pd(c1, m, p);
    c2 = _mm512_fmadd_pd(c2, m, p);
  }
  return _mm512_add_pd(_mm512_add_pd(c0, c1), c2);
}
BODY512(t_fmawork, fma_work(a))
BODY512(t_fmawork_sqrt, _mm512_add_pd(fma_work(a), _mm512_sqrt_pd(a)))
BODY512(t_fmawork_div, _mm512_add_pd(fma_work(a), _mm512_div_pd(one, a)))

static uint64_t rng = 88172645463325252ull;
static uint64_t xorshift(void) {
  rng ^= rng << 13;
  rng ^= rng >> 7;
  rng ^= rng << 17;
  return rng;
}

/* A positive double: random mantissa, exponent in [e0, e1]. */
static double rand_pos(int e0, int e1) {
  const uint64_t m = xorshift() & ((1ull << 52) - 1);
  const int e = e0 + (int)(xorshift() % (uint64_t)(e1 - e0 + 1));
  uint64_t b = ((uint64_t)(e + 1023) << 52) | m;
  double d;
  memcpy(&d, &b, sizeof d);
  return d;
}

/* ex_sqrt, ex_rcp against vsqrtpd, vdivpd on n vectors; returns the number of lanes that differ. */
static long check(long n) {
  long bad = 0;
  double a[8], s[8], q[8];
  static const double edge[] = {0.0,
                                -0.0,
                                1.0,
                                2.0,
                                4.0,
                                0.25,
                                3.0,
                                0x1p-1022,
                                0x1p-1074,
                                0x1.fffffffffffffp1023,
                                INFINITY,
                                0x1.fffffffffffffp0,
                                0x1.0000000000001p0,
                                0x1.fffffffffffffp-1,
                                1e-300,
                                1e300};
  const long n_edge = (long)(sizeof edge / sizeof edge[0]);
  for (long v = 0; v < n; ++v) {
    for (int l = 0; l < 8; ++l) {
      const long i = v * 8 + l;
      if (i < n_edge)
        a[l] = edge[i];
      else if (v % 4 == 0)
        a[l] = rand_pos(-1022, 1023); /* any normal */
      else if (v % 4 == 1) {
        /* squares of doubles and their neighbours: the cases nearest a rounding boundary */
        const double r = rand_pos(-20, 20), sq = r * r;
        uint64_t b;
        memcpy(&b, &sq, sizeof b);
        b += (xorshift() % 5) - 2;
        memcpy(&a[l], &b, sizeof b);
      } else
        a[l] = rand_pos(-8, 8); /* bond lengths squared, in any unit */
    }
    const __m512d va = _mm512_loadu_pd(a);
    _mm512_storeu_pd(s, ex_sqrt8(va));
    _mm512_storeu_pd(q, ex_rcp8(va));
    double s4[8], q4[8];
    _mm256_storeu_pd(s4, ex_sqrt4(_mm256_loadu_pd(a)));
    _mm256_storeu_pd(s4 + 4, ex_sqrt4(_mm256_loadu_pd(a + 4)));
    _mm256_storeu_pd(q4, ex_rcp4(_mm256_loadu_pd(a)));
    _mm256_storeu_pd(q4 + 4, ex_rcp4(_mm256_loadu_pd(a + 4)));
    for (int l = 0; l < 8; ++l) {
      const double rs = sqrt(a[l]), rq = 1.0 / a[l];
      if (memcmp(&rs, &s[l], 8)) {
        if (bad < 10) printf("  sqrt(%a): %a, expected %a\n", a[l], s[l], rs);
        ++bad;
      }
      if (memcmp(&rs, &s4[l], 8) || memcmp(&rq, &q4[l], 8)) {
        if (bad < 10) printf("  ymm: sqrt(%a) %a, 1/a %a\n", a[l], s4[l], q4[l]);
        ++bad;
      }
      if (memcmp(&rq, &q[l], 8)) {
        if (bad < 10) printf("  1/%a: %a, expected %a\n", a[l], q[l], rq);
        ++bad;
      }
    }
  }
  return bad;
}

static double med5(double (*f)(void)) {
  double t[5];
  for (int k = 0; k < 5; ++k)
    t[k] = f();
  qsort(t, 5, sizeof t[0], cmp_double);
  return t[2];
}

int main(int argc, char **argv) {
  long n_check = 1L << 22;
  for (int i = 1; i < argc; ++i) {
    if (!strcmp(argv[i], "--reps") && i + 1 < argc)
      reps = atol(argv[++i]);
    else if (!strcmp(argv[i], "--check") && i + 1 < argc)
      n_check = atol(argv[++i]);
    else {
      fprintf(stderr, "usage: bench_ops [--reps N] [--check N]\n");
      return 2;
    }
  }
  __builtin_cpu_init();
  if (!__builtin_cpu_supports("avx512f")) {
    printf("bench_ops: this CPU has no AVX-512; nothing measured\n");
    return 0;
  }
  for (int k = 0; k < N; ++k) {
    in[k] = 1.0 + (double)(k % 97) / 37.0 + 1e-3 * (double)k;
    idx[k] = (int32_t)((k * 389) % N);
  }
  const double t_add = med5(t_chain), ghz = 4.0 / t_add;
  printf("clock: %.3f ns per dependent add -> %.2f GHz (addsd latency 4 cycles)\n", 1e9 * t_add,
         1e-9 * ghz);
  const double t256 = med5(t_clock256), t512 = med5(t_clock512);
  printf("clock beside 256-bit FMAs: %.2f GHz; beside 512-bit FMAs: %.2f GHz\n", 4e-9 / t256,
         4e-9 / t512);
  printf("%-34s %10s %10s %10s\n", "operation", "ns/instr", "cyc/instr", "cyc/double");
  struct {
    const char *name;
    double (*f)(void);
    int w;
  } ops[] = {
      {"load + add (ymm, the harness)", t_load256, 4},
      {"load + add (zmm, the harness)", t_load512, 8},
      {"vsqrtpd ymm", t_sqrt256, 4},
      {"vsqrtpd zmm", t_sqrt512, 8},
      {"vdivpd ymm", t_div256, 4},
      {"vdivpd zmm", t_div512, 8},
      {"vrsqrt14pd zmm", t_rsqrt14_512, 8},
      {"vfmadd ymm, 8 chains", t_fmachain256, 4},
      {"vfmadd zmm, 8 chains", t_fmachain512, 8},
      {"vgatherdpd ymm (L1)", t_gather256, 4},
      {"vgatherdpd zmm (L1)", t_gather512, 8},
      {"exact sqrt, FMA steps (zmm)", t_exsqrt512, 8},
      {"exact 1/a, FMA steps (zmm)", t_exrcp512, 8},
      {"exact sqrt, FMA steps (ymm)", t_exsqrt256, 4},
      {"exact 1/a, FMA steps (ymm)", t_exrcp256, 4},
      {"24 FMAs (zmm)", t_fmawork, 8},
      {"24 FMAs + vsqrtpd (zmm)", t_fmawork_sqrt, 8},
      {"24 FMAs + vdivpd (zmm)", t_fmawork_div, 8},
      {"vsqrtpd + vsqrtpd (zmm)", t_mix2sqrt, 16},
      {"vsqrtpd + exact sqrt (zmm)", t_mixsqrt, 16},
      {"exact sqrt + exact sqrt (zmm)", t_mix2ex, 16},
  };
  for (size_t o = 0; o < sizeof ops / sizeof ops[0]; ++o) {
    const double t = med5(ops[o].f);
    printf("%-34s %10.3f %10.2f %10.2f\n", ops[o].name, 1e9 * t, t * ghz, t * ghz / ops[o].w);
  }
  const long bad = check(n_check);
  printf("exact sqrt and 1/a against vsqrtpd, vdivpd: %ld vectors of 8, %ld lanes differ\n",
         n_check, bad);
  return bad != 0;
}
#else
int main(void) {
  printf("bench_ops: x86-64 with GCC or Clang only\n");
  return 0;
}
#endif
