/* Family build benchmark: simple cubic (3-D) or square (2-D) lattice blocks of about 1e5 and 1e6
 * particles, horizon 3.015 spacings (about 118 bonds per particle in a free cube, 28 in the 2-D
 * bulk), reordered by Morton key of the family cells first (timed separately), then built R times
 * per configuration (kernels ref | simd x threads 1 | 2), configurations interleaved within each
 * repeat so machine noise spreads over all of them; the median is reported.
 *
 *   bench_families [--n N]... [--dim 2|3] [--threads T]... [--repeat R] [--kernels ref|simd]
 *                  [--order morton|lattice|random]
 *
 * Checks that every configuration builds bitwise the same families (hash of bond_start, bond_j).
 * Prints, per configuration: median build time (wall, and CPU time of all threads), the time to
 * allocate and first-touch a fresh array the size of bond_j on as many threads (touch_s: the
 * page-fault floor), particles/s,
 * directed bonds/s, bonds per particle, bytes held per bond (bond_j alone, and with bond_start),
 * and the process's peak memory.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "pdk/pdk.h"

#define MAX_LIST 8

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

static double median(double *v, int n) {
  qsort(v, (size_t)n, sizeof *v, cmp_double);
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* CPU time of the whole process (all threads) [s]: on a shared machine it does not count the time
 * other jobs held the cores, so it is the steadier number to compare variants by. */
static double cpu_time(void) {
  struct timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A 64-bit hash of the CSR arrays (word-wise multiply-xorshift): every configuration must give
 * the same families. */
static uint64_t hash_words(uint64_t h, const void *data, size_t bytes) {
  const unsigned char *b = data;
  for (size_t k = 0; k < bytes; k += 8) {
    uint64_t w = 0;
    memcpy(&w, b + k, bytes - k < 8 ? bytes - k : 8);
    h = (h ^ w) * 0x9e3779b97f4a7c15ull;
    h ^= h >> 29;
  }
  return h;
}

static uint64_t families_hash(const pdk_families *f) {
  uint64_t h = hash_words(1469598103934665603ull, pdk_families_bond_start(f),
                          ((size_t)pdk_families_num_particles(f) + 1) * sizeof(pdk_bond_index));
  return hash_words(h, pdk_families_bond_j(f),
                    (size_t)pdk_families_num_bonds(f) * sizeof(pdk_index));
}

/* Seconds to allocate and first-touch (write) `bytes` fresh bytes with `threads` threads, static
 * schedule: the page-fault floor of any build that produces a bond_j of that size. */
static double touch_floor(size_t bytes, int threads) {
  const double t0 = pdk_wtime();
  unsigned char *a = malloc(bytes);
  if (!a) return -1;
  const long pages = (long)((bytes + 4095) / 4096);
#pragma omp parallel for default(none) shared(a, pages, bytes) schedule(static) num_threads(threads)
  for (long q = 0; q < pages; ++q) {
    const size_t off = (size_t)q * 4096, len = bytes - off < 4096 ? bytes - off : 4096;
    memset(a + off, 1, len);
  }
  const double dt = pdk_wtime() - t0;
  free(a);
  return dt;
}

static void usage(void) {
  fprintf(stderr, "usage: bench_families [--n N]... [--dim 2|3] [--threads T]... [--repeat R]\n"
                  "                      [--kernels ref|simd] [--order morton|lattice|random]\n");
  exit(2);
}

/* Lattice block of about n points (side = round(n^(1/dim))), spacing dx, x fastest. */
static pdk_particles *make_lattice(pdk_ctx *ctx, int dim, long n_target, double dx) {
  long side = 1;
  while ((dim == 3 ? (side + 1) * (side + 1) * (side + 1) : (side + 1) * (side + 1)) <= n_target)
    ++side;
  /* pick the side whose point count is nearest n_target */
  long lo = dim == 3 ? side * side * side : side * side;
  long hi = dim == 3 ? (side + 1) * (side + 1) * (side + 1) : (side + 1) * (side + 1);
  if (hi - n_target < n_target - lo) ++side;
  const long n = dim == 3 ? side * side * side : side * side;
  pdk_particles *p = NULL;
  if (pdk_particles_create(ctx, dim, (pdk_index)n, &p)) {
    fprintf(stderr, "%s\n", pdk_ctx_error_message(ctx));
    exit(1);
  }
  for (long q = 0; q < n; ++q) {
    long idx[3] = {q % side, (q / side) % side, q / (side * side)};
    for (int a = 0; a < dim; ++a)
      pdk_particles_X(p, a)[q] = (idx[a] + 0.5) * dx;
  }
  return p;
}

static void shuffle(pdk_particles *p, uint64_t seed) {
  const pdk_index n = pdk_particles_count(p);
  pdk_index *perm = malloc((size_t)n * sizeof *perm);
  for (pdk_index i = 0; i < n; ++i)
    perm[i] = i;
  for (pdk_index i = n - 1; i > 0; --i) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    pdk_index k = (pdk_index)((seed >> 33) % (uint64_t)(i + 1));
    pdk_index t = perm[i];
    perm[i] = perm[k];
    perm[k] = t;
  }
  pdk_particles_permute(p, perm);
  free(perm);
}

int main(int argc, char **argv) {
  long ns[MAX_LIST] = {100000, 1000000};
  int num_n = 2, dims[2] = {3, 2}, num_dims = 2, threads[MAX_LIST] = {1, 2}, num_threads = 2;
  int repeat = 5, user_n = 0, user_threads = 0;
  const char *kernels[2] = {"ref", "simd"};
  int num_kernels = 2;
  const char *order = "morton";
  for (int k = 1; k < argc; ++k) {
    if (!strcmp(argv[k], "--n") && k + 1 < argc) {
      if (!user_n) num_n = 0, user_n = 1;
      if (num_n < MAX_LIST) ns[num_n++] = atol(argv[++k]);
    } else if (!strcmp(argv[k], "--dim") && k + 1 < argc) {
      dims[0] = atoi(argv[++k]);
      num_dims = 1;
      if (dims[0] != 2 && dims[0] != 3) usage();
    } else if (!strcmp(argv[k], "--threads") && k + 1 < argc) {
      if (!user_threads) num_threads = 0, user_threads = 1;
      if (num_threads < MAX_LIST) threads[num_threads++] = atoi(argv[++k]);
    } else if (!strcmp(argv[k], "--repeat") && k + 1 < argc) {
      repeat = atoi(argv[++k]);
      if (repeat < 1) usage();
    } else if (!strcmp(argv[k], "--kernels") && k + 1 < argc) {
      kernels[0] = argv[++k];
      num_kernels = 1;
    } else if (!strcmp(argv[k], "--order") && k + 1 < argc) {
      order = argv[++k];
      if (strcmp(order, "morton") && strcmp(order, "lattice") && strcmp(order, "random")) usage();
    } else {
      usage();
    }
  }

  pdk_ctx *ctx[2] = {NULL, NULL};
  for (int k = 0; k < num_kernels; ++k) {
    pdk_ctx_opts o = pdk_ctx_opts_default();
    o.kernels = kernels[k];
    o.num_threads = 0;
    char why[512];
    if (pdk_ctx_create(&o, &ctx[k], why, sizeof why)) {
      fprintf(stderr, "pdk_ctx_create: %s\n", why);
      return 1;
    }
  }
  printf("# bench_families: horizon 3.015 dx, order %s, median of %d repeats\n", order, repeat);
  printf("# %-3s %-8s %-5s %-3s %10s %10s %9s %8s %12s %12s %8s %8s %9s %10s\n", "dim", "n", "kern",
         "thr", "reorder_s", "build_s", "cpu_s", "touch_s", "particles/s", "bonds/s", "bonds/p",
         "B/bond", "B/bond+s", "peak_MiB");
  const double dx = 1e-3, horizon = 3.015 * dx;
  for (int d = 0; d < num_dims; ++d) {
    for (int in = 0; in < num_n; ++in) {
      const int dim = dims[d];
      pdk_particles *p[2] = {NULL, NULL};
      double reorder_s[2] = {0, 0};
      for (int k = 0; k < num_kernels; ++k) {
        p[k] = make_lattice(ctx[k], dim, ns[in], dx);
        double t0 = pdk_wtime();
        if (!strcmp(order, "morton")) {
          if (pdk_particles_reorder_morton(p[k], pdk_families_cell_edge(p[k], horizon), NULL)) {
            fprintf(stderr, "%s\n", pdk_ctx_error_message(ctx[k]));
            return 1;
          }
        } else if (!strcmp(order, "random")) {
          shuffle(p[k], 42);
        }
        reorder_s[k] = pdk_wtime() - t0;
      }
      const pdk_index n = pdk_particles_count(p[0]);
      double *times = malloc((size_t)num_kernels * num_threads * repeat * sizeof *times);
      double *cpu = malloc((size_t)num_kernels * num_threads * repeat * sizeof *cpu);
      double *floor_s = malloc((size_t)num_threads * repeat * sizeof *floor_s);
      long long bonds[2] = {0, 0};
      uint64_t hash = 0;
      size_t bytes[2] = {0, 0};
      for (int r = 0; r < repeat; ++r) {
        for (int k = 0; k < num_kernels; ++k) {
          for (int t = 0; t < num_threads; ++t) {
            if (pdk_ctx_set_num_threads(ctx[k], threads[t])) {
              fprintf(stderr, "%s\n", pdk_ctx_error_message(ctx[k]));
              return 1;
            }
            pdk_families_opts o = pdk_families_opts_default();
            o.horizon = horizon;
            pdk_families *f = NULL;
            double t0 = pdk_wtime(), c0 = cpu_time();
            if (pdk_families_build(p[k], &o, &f)) {
              fprintf(stderr, "%s\n", pdk_ctx_error_message(ctx[k]));
              return 1;
            }
            times[(k * num_threads + t) * repeat + r] = pdk_wtime() - t0;
            cpu[(k * num_threads + t) * repeat + r] = cpu_time() - c0;
            bonds[k] = pdk_families_num_bonds(f);
            if (r == 0) { /* same families for every kernel family and thread count */
              const uint64_t h = families_hash(f);
              if (k == 0 && t == 0) hash = h;
              if (h != hash) {
                fprintf(stderr,
                        "%d-D n = %d: families with %s kernels on %d threads differ from "
                        "the first configuration\n",
                        dim, (int)n, kernels[k], threads[t]);
                return 1;
              }
            }
            bytes[k] = pdk_families_memory_bytes(f);
            pdk_families_destroy(&f);
          }
        }
        for (int t = 0; t < num_threads; ++t)
          floor_s[t * repeat + r] = touch_floor((size_t)bonds[0] * sizeof(pdk_index), threads[t]);
      }
      for (int k = 0; k < num_kernels; ++k) {
        for (int t = 0; t < num_threads; ++t) {
          double med = median(times + (k * num_threads + t) * repeat, repeat);
          double med_cpu = median(cpu + (k * num_threads + t) * repeat, repeat);
          double med_floor = median(floor_s + t * repeat, repeat);
          printf("  %-3d %-8d %-5s %-3d %10.4f %10.4f %9.4f %8.4f %12.4g %12.4g %8.2f %8.2f %9.3f "
                 "%10.1f\n",
                 dim, (int)n, kernels[k], threads[t], reorder_s[k], med, med_cpu, med_floor,
                 n / med, bonds[k] / med, (double)bonds[k] / n, 4.0,
                 (double)bytes[k] / (double)bonds[k], (double)pdk_peak_memory_bytes() / (1 << 20));
        }
      }
      fflush(stdout);
      free(times);
      free(cpu);
      free(floor_s);
      for (int k = 0; k < num_kernels; ++k)
        pdk_particles_destroy(&p[k]);
    }
  }
  for (int k = 0; k < num_kernels; ++k)
    pdk_ctx_destroy(&ctx[k]);
  return 0;
}
