/* tests/test_sample.c - mlod_sample, the importance sampling that chooses
   views (virtual point lights) from candidates: its samples follow the
   importance (a chi-square test on a small domain, and one that must fail
   for uniform samples), its weighted estimate is exact on average where
   the integrand is proportional to the importance (the mean over many
   seeds against the known sum), the inverse transform's for any integrand,
   Metropolis-Hastings keeps its samples where the importance changes
   elsewhere (the reason to use it) while the inverse transform moves them,
   and it is deterministic for a seed, for any thread count, refuses bad
   input and leaves its outputs untouched then. */
#define MANYLODS_IMPLEMENTATION
#define MANYLODS_PTHREADS
#include "../manylods.h"
#include "testutil.h"

#define MAX_SAMPLES 8192

static uint32_t samples[MAX_SAMPLES], other[MAX_SAMPLES];
static float weights[MAX_SAMPLES], other_weights[MAX_SAMPLES];

static uint64_t rng_state = 12345;
static double rng01(void) { return scene_rng_double(&rng_state); }

static mlod_sample_params params_of(mlod_sampler method, uint32_t chain_length, uint64_t seed)
{
    mlod_sample_params p;
    memset(&p, 0, sizeof p);
    p.method = method;
    p.chain_length = chain_length;
    p.seed = seed;
    return p;
}

static const char *name_of(mlod_sampler method)
{
    return method == MLOD_SAMPLER_METROPOLIS ? "Metropolis" : "inverse transform";
}

/* Pearson's chi-square of the counts of n samples against importance f
   (over the candidates with f > 0; *zero_hits: samples of candidates with
   f = 0). */
static double chi_square(const float *f, uint32_t d, const uint32_t *s, uint32_t n, uint32_t *zero_hits)
{
    double total = 0.0, chi = 0.0;
    uint32_t counts[64] = {0}, i;
    *zero_hits = 0;
    for (i = 0; i < d; i++) total += f[i];
    for (i = 0; i < n; i++) counts[s[i]]++;
    for (i = 0; i < d; i++) {
        double expected = n * (f[i] / total);
        if (f[i] == 0.0f) {
            *zero_hits += counts[i];
            continue;
        }
        chi += (counts[i] - expected) * (counts[i] - expected) / expected;
    }
    return chi;
}

/* Samples follow the importance: chi-square below its 0.999 quantile for
   13 degrees of freedom (14 candidates above 0), for sample counts whose
   prime factors differ (the chains' bases are the primes they lack), and
   never a candidate of importance 0.  One chain step (uniform samples)
   must fail the same test: the test can tell. */
static void test_distribution(void)
{
    static const uint32_t counts[4] = {4096, 3003, 4095, 7919};
    const double quantile = 34.53; /* chi-square, 13 degrees of freedom, p = 0.999 */
    float f[16];
    uint32_t i, c, zero_hits;
    int m;
    mlod_error e;
    for (i = 0; i < 16; i++) f[i] = (float)(0.25 + 3.75 * rng01());
    f[3] = 0.0f;
    f[11] = 0.0f;
    f[7] = 8.0f; /* a peak */
    for (m = 0; m < 2; m++)
        for (c = 0; c < 4; c++) {
            mlod_sampler method = m ? MLOD_SAMPLER_METROPOLIS : MLOD_SAMPLER_INVERSE_TRANSFORM;
            mlod_sample_params p = params_of(method, 64, 7 + c);
            double chi;
            CHECK(mlod_sample(f, 16, counts[c], &p, samples, weights, &e) == MLOD_OK, "%s: sample: %s", name_of(method),
                  e.message);
            chi = chi_square(f, 16, samples, counts[c], &zero_hits);
            CHECK(chi < quantile, "%s, N = %u: chi-square %.2f against the importance, below %.2f expected",
                  name_of(method), counts[c], chi, quantile);
            CHECK(zero_hits == 0, "%s, N = %u: %u samples of candidates of importance 0", name_of(method), counts[c],
                  zero_hits);
        }
    {
        mlod_sample_params p = params_of(MLOD_SAMPLER_METROPOLIS, 1, 7);
        f[3] = f[11] = 1.0f; /* one step samples every candidate */
        CHECK(mlod_sample(f, 16, 4096, &p, samples, weights, &e) == MLOD_OK, "one step: %s", e.message);
        CHECK(chi_square(f, 16, samples, 4096, &zero_hits) > 10.0 * quantile,
              "one chain step is uniform sampling, far from the importance (chi-square %.1f)",
              chi_square(f, 16, samples, 4096, &zero_hits));
    }
}

/* The weighted estimate (1/N) sum w_j g(s_j) of sum_i g(i). */
static double estimate(const float *g, uint32_t n)
{
    double sum = 0.0;
    uint32_t j;
    for (j = 0; j < n; j++) sum += (double)weights[j] * g[samples[j]];
    return sum / n;
}

/* The mean over seeds of the estimate against the exact sum, within four
   standard errors (and the inverse transform exact for every seed where g
   is proportional to f); for g not proportional to f, Metropolis-Hastings
   is biased for short chains (its start-up bias): with 64 steps, within
   1 % here. */
static void test_unbiased(void)
{
    enum { D = 200, N = 256, SEEDS = 400 };
    float f[D], g[D], h[D];
    double sum_g = 0.0, sum_h = 0.0;
    uint32_t i;
    int m, which;
    mlod_error e;
    for (i = 0; i < D; i++) {
        f[i] = (float)(i % 17 == 0 ? 0.0 : 0.1 + rng01() * (i < 50 ? 5.0 : 1.0));
        g[i] = 3.0f * f[i];                                     /* proportional */
        h[i] = f[i] > 0.0f ? (float)(0.5 + rng01()) * f[i] : 0.0f; /* not */
        sum_g += g[i];
        sum_h += h[i];
    }
    for (m = 0; m < 2; m++)
        for (which = 0; which < 2; which++) {
            mlod_sampler method = m ? MLOD_SAMPLER_METROPOLIS : MLOD_SAMPLER_INVERSE_TRANSFORM;
            const float *integrand = which ? h : g;
            double exact = which ? sum_h : sum_g, mean = 0.0, square = 0.0, se, worst = 0.0;
            uint32_t seed;
            for (seed = 0; seed < SEEDS; seed++) {
                mlod_sample_params p = params_of(method, which ? 64 : 4, 1000 + seed);
                double x;
                if (mlod_sample(f, D, N, &p, samples, weights, &e) != MLOD_OK) {
                    CHECK(0, "unbiased: %s", e.message);
                    return;
                }
                x = estimate(integrand, N);
                mean += x;
                square += x * x;
                if (fabs(x - exact) > worst) worst = fabs(x - exact);
            }
            mean /= SEEDS;
            se = sqrt(fmax(square / SEEDS - mean * mean, 0.0) / (SEEDS - 1));
            if (m == 0 && which == 0)
                CHECK(worst <= 1e-5 * exact, "inverse transform, g = 3 f: every estimate exact (worst %.3g of %.6g)",
                      worst, exact);
            else if (m == 1 && which == 1)
                CHECK(fabs(mean - exact) <= 0.01 * exact + 4.0 * se,
                      "Metropolis (64 steps), g not proportional to f: mean %.6g, exact %.6g (standard error %.3g)",
                      mean, exact, se);
            else
                CHECK(fabs(mean - exact) <= 4.0 * se + 1e-9 * exact,
                      "%s, %s: mean %.6g over %d seeds, exact %.6g (standard error %.3g)", name_of(method),
                      which ? "g not proportional to f" : "g = 3 f", mean, SEEDS, exact, se);
        }
}

/* Metropolis-Hastings' bias where g is not proportional to f, as the
   manual states it (MLOD_SAMPLER_METROPOLIS): importances spread over 51
   times (0.1 + 5 u on a quarter of the candidates, 0.1 + u elsewhere),
   g = 1 (each candidate counted once, g / f as varied as f): low by about
   12 % at M = 4, 7 % at 16, 2 % at 64, under 1 % at 256, never above; g
   within [0.5, 1.5] f: within 2 % at every M. */
static void test_bias(void)
{
    enum { D = 4096, N = 1024, SEEDS = 100 };
    static float f[D], g[D], one[D];
    static const uint32_t M[4] = {4, 16, 64, 256};
    static const double most[4] = {0.15, 0.09, 0.03, 0.01}, least[4] = {0.08, 0.04, 0.005, -0.005};
    double sum_g = 0.0, bias[4], bias_g[4];
    uint32_t i, k, seed;
    mlod_error e;
    for (i = 0; i < D; i++) {
        f[i] = (float)(0.1 + rng01() * (i < D / 4 ? 5.0 : 1.0));
        g[i] = (float)(0.5 + rng01()) * f[i];
        one[i] = 1.0f;
        sum_g += g[i];
    }
    for (k = 0; k < 4; k++) {
        double mean = 0.0, mean_g = 0.0;
        for (seed = 0; seed < SEEDS; seed++) {
            mlod_sample_params p = params_of(MLOD_SAMPLER_METROPOLIS, M[k], 7000 + seed);
            if (mlod_sample(f, D, N, &p, samples, weights, &e) != MLOD_OK) {
                CHECK(0, "bias: %s", e.message);
                return;
            }
            mean += estimate(one, N);
            mean_g += estimate(g, N);
        }
        bias[k] = mean / SEEDS / D - 1.0;
        bias_g[k] = mean_g / SEEDS / sum_g - 1.0;
        CHECK(bias[k] <= -least[k] && bias[k] >= -most[k] && fabs(bias_g[k]) <= 0.02,
              "Metropolis, M = %u: g = 1 %+.2f %% (the manual: low by %.1f to %.1f %%), g within [0.5, 1.5] f %+.2f %% "
              "(within 2 %%)", M[k], 100.0 * bias[k], 100.0 * least[k], 100.0 * most[k], 100.0 * bias_g[k]);
    }
    printf("  Metropolis bias, g = 1: %+.1f %%, %+.1f %%, %+.1f %%, %+.1f %% at M = 4, 16, 64, 256\n", 100.0 * bias[0],
           100.0 * bias[1], 100.0 * bias[2], 100.0 * bias[3]);
}

/* A local change of the importance (32 neighbouring candidates of 4096
   three times as important) keeps most Metropolis samples where they
   were; the inverse transform shifts most of its own. */
static void test_coherence(void)
{
    enum { D = 4096, N = 1024 };
    static float f[D], changed[D];
    uint32_t i, j;
    int m;
    double kept[2];
    mlod_error e;
    for (i = 0; i < D; i++) f[i] = changed[i] = (float)(0.2 + rng01());
    for (i = 100; i < 132; i++) changed[i] *= 3.0f;
    for (m = 0; m < 2; m++) {
        mlod_sampler method = m ? MLOD_SAMPLER_METROPOLIS : MLOD_SAMPLER_INVERSE_TRANSFORM;
        mlod_sample_params p = params_of(method, 16, 99);
        uint32_t same = 0;
        CHECK(mlod_sample(f, D, N, &p, samples, weights, &e) == MLOD_OK, "coherence: %s", e.message);
        CHECK(mlod_sample(changed, D, N, &p, other, other_weights, &e) == MLOD_OK, "coherence: %s", e.message);
        for (j = 0; j < N; j++) same += samples[j] == other[j];
        kept[m] = (double)same / N;
    }
    CHECK(kept[1] >= 0.9, "Metropolis keeps %.1f %% of its samples when 32 candidates of %d change (>= 90 %%)",
          100.0 * kept[1], D);
    CHECK(kept[0] <= 0.5, "the inverse transform keeps %.1f %% of its samples (it moves most: <= 50 %%)",
          100.0 * kept[0]);
}

/* The same seed gives the same samples and weights, with or without
   threads; another seed gives others. */
static void test_determinism(void)
{
    enum { D = 5000, N = 5000 };
    static float f[D];
    mlod_pool *pools[2] = {mlod_pool_create(2), mlod_pool_create(3)};
    uint32_t i;
    int m, k;
    mlod_error e;
    CHECK(pools[0] && pools[1], "determinism: pools");
    if (!pools[0] || !pools[1]) return;
    for (i = 0; i < D; i++) f[i] = (float)rng01();
    for (m = 0; m < 2; m++) {
        mlod_sampler method = m ? MLOD_SAMPLER_METROPOLIS : MLOD_SAMPLER_INVERSE_TRANSFORM;
        mlod_sample_params p = params_of(method, 8, 5);
        uint32_t differ = 0;
        CHECK(mlod_sample(f, D, N, &p, samples, weights, &e) == MLOD_OK, "determinism: %s", e.message);
        for (k = 0; k < 3; k++) {
            mlod_parallel hook;
            if (k < 2) {
                hook = mlod_pool_parallel(pools[k]);
                p.parallel = &hook;
            } else {
                p.parallel = NULL;
            }
            memset(other, 0xff, sizeof other);
            CHECK(mlod_sample(f, D, N, &p, other, other_weights, &e) == MLOD_OK, "determinism: %s", e.message);
            CHECK(memcmp(samples, other, N * sizeof *other) == 0 && memcmp(weights, other_weights, N * sizeof *weights) == 0,
                  "%s: the same seed gives the same samples and weights (%s)", name_of(method),
                  k == 0 ? "2 threads" : k == 1 ? "3 threads" : "again, no threads");
        }
        for (i = 0; i < N; i++) {
            CHECK(samples[i] < D && isfinite(weights[i]) && weights[i] >= 0.0f, "%s: sample %u: %u, weight %g",
                  name_of(method), i, samples[i], (double)weights[i]);
            if (samples[i] >= D || !isfinite(weights[i])) break;
        }
        p.seed = 6;
        p.parallel = NULL;
        CHECK(mlod_sample(f, D, N, &p, other, other_weights, &e) == MLOD_OK, "determinism: %s", e.message);
        for (i = 0; i < N; i++) differ += samples[i] != other[i];
        CHECK(differ > N / 2, "%s: another seed gives other samples (%u of %d differ)", name_of(method), differ, N);
    }
    mlod_pool_destroy(pools[0]);
    mlod_pool_destroy(pools[1]);
}

/* While the chains' proposals fit in the domain (N M <= D) no candidate is
   proposed twice, so no two samples are the same candidate; beyond, they
   repeat (each candidate once per D proposals). */
static void test_distinct(void)
{
    enum { D = 4096 };
    static float f[D];
    static uint8_t seen[D];
    uint32_t i, repeats = 0;
    int c;
    mlod_error e;
    for (i = 0; i < D; i++) f[i] = (float)(0.05 + rng01() * (i % 64 == 0 ? 50.0 : 1.0)); /* peaks the chains crowd to */
    for (c = 0; c < 2; c++) {
        mlod_sample_params p = params_of(MLOD_SAMPLER_METROPOLIS, c ? 64 : 16, 3);
        CHECK(mlod_sample(f, D, 256, &p, samples, weights, &e) == MLOD_OK, "distinct: %s", e.message);
        memset(seen, 0, sizeof seen);
        repeats = 0;
        for (i = 0; i < 256; i++) repeats += seen[samples[i]]++ != 0;
        if (c == 0)
            CHECK(repeats == 0, "N M = D: %u samples repeat a candidate, none expected", repeats);
        else
            CHECK(repeats > 0, "N M = 4 D: candidates repeat (%u samples), the chains meet at the peaks", repeats);
    }
}

static void *refusing_alloc(void *user, size_t bytes)
{
    (void)user;
    (void)bytes;
    return NULL;
}

static void ignoring_free(void *user, void *p)
{
    (void)user;
    (void)p;
}

/* Bad input: an error with a message, the outputs untouched.  Importance
   0 everywhere: uniform samples of weight 0. */
static void test_errors(void)
{
    float f[4] = {1.0f, 2.0f, 0.0f, 3.0f}, bad[4];
    mlod_sample_params p = params_of(MLOD_SAMPLER_INVERSE_TRANSFORM, 0, 1), q = p;
    mlod_allocator refusing = {refusing_alloc, ignoring_free, NULL};
    mlod_error e;
    uint32_t i;
    struct {
        const float *f;
        uint32_t d, n;
        const mlod_sample_params *p;
        mlod_result expected;
        const char *what;
    } cases[9];
    int k, count = 0;
    memcpy(bad, f, sizeof f);
#define CASE(F, D, N, P, R, W)                                                                                       \
    do {                                                                                                             \
        cases[count].f = F;                                                                                          \
        cases[count].d = D;                                                                                          \
        cases[count].n = N;                                                                                          \
        cases[count].p = P;                                                                                          \
        cases[count].expected = R;                                                                                   \
        cases[count++].what = W;                                                                                     \
    } while (0)
    CASE(NULL, 4, 4, &p, MLOD_ERROR_INVALID_ARGUMENT, "no importance");
    CASE(f, 4, 4, NULL, MLOD_ERROR_INVALID_ARGUMENT, "no params");
    CASE(f, 0, 4, &p, MLOD_ERROR_EMPTY, "an empty domain");
    CASE(f, 4, 0, &p, MLOD_ERROR_EMPTY, "no samples");
    CASE(bad, 4, 4, &p, MLOD_ERROR_INVALID_ARGUMENT, "a negative importance");
    CASE(bad, 4, 4, &p, MLOD_ERROR_NON_FINITE, "a NaN importance");
    CASE(bad, 4, 4, &p, MLOD_ERROR_RANGE, "weights beyond float range");
    CASE(f, 4, 4, &q, MLOD_ERROR_INVALID_ARGUMENT, "an unknown method");
    CASE(f, 4, 4, &q, MLOD_ERROR_OUT_OF_MEMORY, "a refused table");
    for (k = 0; k < count; k++) {
        if (k == 4) bad[1] = -1.0f;
        if (k == 5) bad[1] = (float)NAN;
        if (k == 6) {
            bad[1] = 1e-30f;
            bad[3] = 1e30f;
        }
        if (k == 7) q.method = (mlod_sampler)7;
        if (k == 8) {
            q.method = MLOD_SAMPLER_INVERSE_TRANSFORM;
            q.allocator = &refusing;
        }
        memset(samples, 0xab, 16);
        memset(weights, 0xab, 16);
        memset(&e, 0, sizeof e);
        CHECK(mlod_sample(cases[k].f, cases[k].d, cases[k].n, cases[k].p, samples, weights, &e) == cases[k].expected &&
                  e.code == cases[k].expected && e.message[0] != '\0',
              "%s: %s expected, got %s (%s)", cases[k].what, mlod_result_name(cases[k].expected),
              mlod_result_name(e.code), e.message);
        for (i = 0; i < 4; i++)
            CHECK(samples[i] == 0xabababab, "%s: samples untouched", cases[k].what);
    }
#undef CASE
    CHECK(mlod_sample(f, 4, 4, &p, NULL, weights, &e) == MLOD_ERROR_INVALID_ARGUMENT, "no sample array refused");
    CHECK(mlod_sample_bound(1000, MLOD_SAMPLER_INVERSE_TRANSFORM) == 1001 * sizeof(double) &&
              mlod_sample_bound(1000, MLOD_SAMPLER_METROPOLIS) == 0 &&
              mlod_sample_bound(1000, (mlod_sampler)7) == (size_t)-1,
          "mlod_sample_bound: the cumulative table, nothing for Metropolis, (size_t)-1 for an unknown method");
    for (i = 0; i < 2; i++) { /* success clears an error left from an earlier call */
        mlod_sample_params ok = params_of(i ? MLOD_SAMPLER_METROPOLIS : MLOD_SAMPLER_INVERSE_TRANSFORM, 4, 3);
        e.code = MLOD_ERROR_EMPTY;
        strcpy(e.message, "stale");
        CHECK(mlod_sample(f, 4, 4, &ok, samples, weights, &e) == MLOD_OK && e.code == MLOD_OK && e.message[0] == '\0',
              "%s: success leaves MLOD_OK and an empty message in the error (%s, '%s')", name_of(ok.method),
              mlod_result_name(e.code), e.message);
    }
    {
        float zero[5] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
        int m;
        for (m = 0; m < 2; m++) {
            mlod_sample_params z = params_of(m ? MLOD_SAMPLER_METROPOLIS : MLOD_SAMPLER_INVERSE_TRANSFORM, 4, 3);
            uint32_t seen = 0;
            CHECK(mlod_sample(zero, 5, 100, &z, samples, weights, &e) == MLOD_OK, "zero importance: %s", e.message);
            for (i = 0; i < 100; i++) {
                CHECK(samples[i] < 5 && weights[i] == 0.0f, "zero importance: sample %u weight %g", samples[i],
                      (double)weights[i]);
                seen |= 1u << (samples[i] & 31);
            }
            CHECK(seen == 31u, "zero importance: every candidate sampled (uniform), mask %x", seen);
        }
    }
}

int main(void)
{
    test_distribution();
    test_unbiased();
    test_bias();
    test_coherence();
    test_determinism();
    test_distinct();
    test_errors();
    return test_finish();
}
