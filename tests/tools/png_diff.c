/* png_diff: compares two images under a tolerance.
 *
 *   png_diff A.png B.png [--max-mean M] [--max-frac F] [--threshold T]
 *
 * Prints the size check, the mean absolute error per channel (0..255) and the
 * fraction of pixels whose largest channel difference exceeds T. Exits 0 when
 * the sizes match, the mean error <= M and the fraction <= F; 1 when they do
 * not; 2 on bad usage or an image that cannot be read (the message names it).
 *
 * Metric: the same as gl_test_golden() in tests/support/gl_test.h. Both images are
 * decoded to RGBA8; the mean is taken over the R, G and B channels of every
 * pixel together (sum / (3 * pixels)), alpha is ignored (printed for
 * information only); a pixel is "off" when its largest R/G/B difference is
 * greater than T.
 * Defaults: T = 32, the threshold gl_test_golden() hard-codes (not 16).
 * gl_test.h has no defaults for M and F (every caller passes its own; the
 * golden tests in tests/gl/test_render.c use M = 4.0, F = 0.03, the cross-driver
 * tolerance of docs/testing.md), so M = 1.0 and F = 0.01 here: tighter, for
 * "the same picture as before" on the same machine.
 *
 * Built by tests/CMakeLists.txt (target png_diff), or by hand with Debian's
 * libstb-dev:
 *   gcc -std=c11 -O2 -Wall -Wextra -I/usr/include/stb tests/tools/png_diff.c -o png_diff -lstb -lm
 */
#include <stb_image.h>

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void usage(FILE *f)
{
    fprintf(f, "usage: png_diff A.png B.png [--max-mean M] [--max-frac F] [--threshold T]\n"
               "  --max-mean M   largest mean absolute R/G/B error, 0..255 (default 1.0)\n"
               "  --max-frac F   largest fraction of pixels off by more than T (default 0.01)\n"
               "  --threshold T  a pixel is off when a channel differs by more than T (default 32)\n"
               "exit: 0 within tolerance, 1 different, 2 bad usage or unreadable image\n");
}

static int parse_number(const char *flag, const char *text, double lo, double hi, double *out)
{
    char *end = NULL;
    errno = 0;
    double v = strtod(text, &end);
    if (errno || end == text || *end != '\0' || !isfinite(v) || v < lo || v > hi) {
        fprintf(stderr, "png_diff: %s needs a number in [%g, %g], got '%s'\n", flag, lo, hi, text);
        return 0;
    }
    *out = v;
    return 1;
}

int main(int argc, char **argv)
{
    const char *path[2] = {NULL, NULL};
    int npath = 0;
    double max_mean = 1.0, max_frac = 0.01, threshold = 32.0;

    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        double *target = NULL;
        double lo = 0.0, hi = 255.0;
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(a, "--max-mean") == 0) {
            target = &max_mean;
        } else if (strcmp(a, "--max-frac") == 0) {
            target = &max_frac;
            hi = 1.0;
        } else if (strcmp(a, "--threshold") == 0) {
            target = &threshold;
        } else if (a[0] == '-' && a[1] == '-') {
            fprintf(stderr, "png_diff: unknown flag '%s'\n", a);
            usage(stderr);
            return 2;
        } else if (npath < 2) {
            path[npath++] = a;
            continue;
        } else {
            fprintf(stderr, "png_diff: too many files ('%s')\n", a);
            usage(stderr);
            return 2;
        }
        if (i + 1 >= argc) {
            fprintf(stderr, "png_diff: %s needs a value\n", a);
            return 2;
        }
        if (!parse_number(a, argv[++i], lo, hi, target)) return 2;
    }
    if (npath != 2) {
        usage(stderr);
        return 2;
    }

    int w[2], h[2], comp[2];
    unsigned char *px[2] = {NULL, NULL};
    for (int k = 0; k < 2; k++) {
        px[k] = stbi_load(path[k], &w[k], &h[k], &comp[k], 4);
        if (!px[k]) {
            fprintf(stderr, "png_diff: cannot read %s: %s\n", path[k], stbi_failure_reason());
            if (k == 1) stbi_image_free(px[0]);
            return 2;
        }
    }

    int same_size = w[0] == w[1] && h[0] == h[1];
    printf("size: %s %dx%d, %s %dx%d: %s\n", path[0], w[0], h[0], path[1], w[1], h[1],
           same_size ? "same" : "DIFFERENT");
    if (!same_size) {
        printf("result: DIFFERENT (size)\n");
        stbi_image_free(px[0]);
        stbi_image_free(px[1]);
        return 1;
    }

    size_t n = (size_t)w[0] * (size_t)h[0], off = 0;
    double sum[4] = {0, 0, 0, 0};
    int worst_any = 0;
    for (size_t i = 0; i < n; i++) {
        int worst = 0;
        for (int c = 0; c < 4; c++) {
            int e = abs((int)px[0][4 * i + c] - (int)px[1][4 * i + c]);
            sum[c] += e;
            if (c < 3 && e > worst) worst = e;
        }
        if (worst > threshold) off++;
        if (worst > worst_any) worst_any = worst;
    }
    double denom = n ? (double)n : 1.0;
    double mean = (sum[0] + sum[1] + sum[2]) / (3.0 * denom);
    double frac = (double)off / denom;
    int ok = mean <= max_mean && frac <= max_frac;
    printf("mean abs error: R %.4f G %.4f B %.4f (A %.4f, not counted); RGB %.4f (max %.4f)\n",
           sum[0] / denom, sum[1] / denom, sum[2] / denom, sum[3] / denom, mean, max_mean);
    printf("pixels off by > %g: %zu of %zu = %.6f (max %.6f); largest channel difference %d\n",
           threshold, off, n, frac, max_frac, worst_any);
    printf("result: %s\n", ok ? "same (within tolerance)" : "DIFFERENT");

    stbi_image_free(px[0]);
    stbi_image_free(px[1]);
    return ok ? 0 : 1;
}
