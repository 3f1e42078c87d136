/* png_region: where two pictures of the same view differ, and what one
 * picture holds, for the viewer and reference tests (tests/cli/cli_view.sh,
 * tests/cli/cli_reference.sh).
 *
 *   png_region A.png B.png CX CY R
 *       Compares B with A inside the disc of radius R pixels around
 *       (CX, CY) and outside a disc of 1.5 R. Prints one line:
 *         inside_mean=M inside_frac=F outside_frac=G shift_x=DX shift_y=DY
 *       M: mean absolute R/G/B difference inside (0..255); F, G: fractions
 *       of pixels inside / outside whose largest channel difference is
 *       above 32 (png_diff's threshold); DX, DY: the whole-pixel shift
 *       (within +-8) that best moves A's disc onto B's (sum of absolute
 *       differences): where the picture under the disc went.
 *   png_region --axis A.png CX CY R
 *       Prints axis=DEG coherence=C: the direction the streaks of the
 *       picture run in the disc (hair seen from the side), from the
 *       structure tensor of the luminance gradient: degrees in [0, 180),
 *       image axes (x right, y down; 0 horizontal, 90 vertical); C in
 *       [0, 1], 0 for no preferred direction.
 *   png_region --red A.png X0 Y0 X1 Y1
 *       Prints red=N: pixels in the box that are clearly red (R > 180,
 *       G and B < 110): the HUD's error colour.
 *   png_region --luma A.png X0 Y0 X1 Y1
 *       Prints luma=L: the mean luminance (BT.601, 0..255) of the pixels
 *       in the box X0 <= x < X1, Y0 <= y < Y1.
 *   png_region --chroma A.png X0 Y0 X1 Y1
 *       Prints chroma_noise=N: colour noise in the box, the mean over its
 *       pixels whose 3 x 3 neighbourhood is lit (R + G + B above 60 in
 *       each) of how far the pixel's chromaticity (r, g over r + g + b)
 *       lies from the mean of its 8 neighbours', x 1000: speckles of
 *       another hue (an 8-bit target rounding many blended layers) raise
 *       it, smooth shading and brightness do not.
 *   png_region --outline A.png X0 X1 R
 *       Prints roughness=P top=T: the top outline of the picture in the
 *       columns X0..X1-1 (per column, the first row from the top whose
 *       largest channel differs from the background, the column's top
 *       pixel, by more than 24), T its mean row, P its roughness: the RMS
 *       of each column's row less the mean over the 2R + 1 columns around
 *       it, in pixels (hair tips standing above their neighbours).
 * Exit 0, or 2 on bad usage or an unreadable image. */
#include <stb_image.h>

#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static unsigned char *load(const char *path, int *w, int *h)
{
    int n;
    unsigned char *p = stbi_load(path, w, h, &n, 4);
    if (!p) fprintf(stderr, "png_region: cannot read '%s': %s\n", path, stbi_failure_reason());
    return p;
}

static int diff(const unsigned char *a, const unsigned char *b)
{
    int m = 0;
    for (int c = 0; c < 3; c++) {
        int d = abs((int)a[c] - (int)b[c]);
        if (d > m) m = d;
    }
    return m;
}

static int outline(const char *path, int x0, int x1, int r)
{
    int w, h;
    unsigned char *a = load(path, &w, &h);
    if (!a) return 2;
    if (x0 < 0) x0 = 0;
    if (x1 > w) x1 = w;
    if (x1 - x0 < 2 || r < 1) {
        fprintf(stderr, "png_region: --outline needs 2 or more columns and R >= 1\n");
        stbi_image_free(a);
        return 2;
    }
    int n = x1 - x0;
    double *top = malloc(sizeof *top * (size_t)n);
    if (!top) {
        stbi_image_free(a);
        return 2;
    }
    double mean = 0.0;
    for (int x = x0; x < x1; x++) {
        int y = 0;
        while (y < h && diff(a + 4 * ((size_t)y * w + x), a + 4 * (size_t)x) <= 24) y++;
        top[x - x0] = y;
        mean += y;
    }
    double sq = 0.0;
    for (int i = 0; i < n; i++) {
        int lo = i - r < 0 ? 0 : i - r, hi = i + r + 1 > n ? n : i + r + 1;
        double local = 0.0;
        for (int j = lo; j < hi; j++) local += top[j];
        local /= hi - lo;
        sq += (top[i] - local) * (top[i] - local);
    }
    printf("roughness=%.3f top=%.2f\n", sqrt(sq / n), mean / n);
    free(top);
    stbi_image_free(a);
    return 0;
}

/* --chroma: colour noise in the box (see the top of this file). */
static int chroma(const char *path, int x0, int y0, int x1, int y1)
{
    int w, h;
    unsigned char *a = load(path, &w, &h);
    if (!a) return 2;
    double sum = 0.0;
    long n = 0;
    for (int y = (y0 < 1 ? 1 : y0); y < y1 && y < h - 1; y++)
        for (int x = (x0 < 1 ? 1 : x0); x < x1 && x < w - 1; x++) {
            double c[2] = {0, 0}, own[2] = {0, 0};
            bool dark = false;
            for (int j = -1; j <= 1; j++)
                for (int i = -1; i <= 1; i++) {
                    const unsigned char *p = a + 4 * ((size_t)(y + j) * w + x + i);
                    double t = (double)p[0] + p[1] + p[2];
                    if (t <= 60.0) { dark = true; continue; }
                    double r = p[0] / t, g = p[1] / t;
                    if (i == 0 && j == 0) own[0] = r, own[1] = g;
                    else c[0] += r / 8.0, c[1] += g / 8.0;
                }
            if (dark) continue;
            sum += hypot(own[0] - c[0], own[1] - c[1]);
            n++;
        }
    printf("chroma_noise=%.3f\n", n ? 1000.0 * sum / (double)n : 0.0);
    stbi_image_free(a);
    return 0;
}

/* --red and --luma: one pass over the box (see the top of this file),
 * printing its clearly red pixels or its mean luminance. */
static int box(const char *path, int x0, int y0, int x1, int y1, bool red)
{
    int w, h;
    unsigned char *a = load(path, &w, &h);
    if (!a) return 2;
    double sum = 0.0;
    long reds = 0, n = 0;
    for (int y = y0 < 0 ? 0 : y0; y < y1 && y < h; y++)
        for (int x = x0 < 0 ? 0 : x0; x < x1 && x < w; x++, n++) {
            const unsigned char *p = a + 4 * ((size_t)y * w + x);
            reds += p[0] > 180 && p[1] < 110 && p[2] < 110;
            sum += 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
        }
    if (red)
        printf("red=%ld\n", reds);
    else
        printf("luma=%.3f\n", n ? sum / (double)n : 0.0);
    stbi_image_free(a);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc == 7 && (!strcmp(argv[1], "--red") || !strcmp(argv[1], "--luma")))
        return box(argv[2], atoi(argv[3]), atoi(argv[4]), atoi(argv[5]), atoi(argv[6]), !strcmp(argv[1], "--red"));
    if (argc == 7 && !strcmp(argv[1], "--chroma"))
        return chroma(argv[2], atoi(argv[3]), atoi(argv[4]), atoi(argv[5]), atoi(argv[6]));
    if (argc == 6 && !strcmp(argv[1], "--axis")) {
        int w, h;
        unsigned char *a = load(argv[2], &w, &h);
        if (!a) return 2;
        double cx = atof(argv[3]), cy = atof(argv[4]), r = atof(argv[5]);
        double jxx = 0.0, jxy = 0.0, jyy = 0.0;
#define LUM(x, y) (0.299 * a[4 * ((size_t)(y) * w + (x))] + 0.587 * a[4 * ((size_t)(y) * w + (x)) + 1] + \
                   0.114 * a[4 * ((size_t)(y) * w + (x)) + 2])
        for (int y = 1; y < h - 1; y++)
            for (int x = 1; x < w - 1; x++) {
                if ((x - cx) * (x - cx) + (y - cy) * (y - cy) > r * r) continue;
                double gx = 0.5 * (LUM(x + 1, y) - LUM(x - 1, y));
                double gy = 0.5 * (LUM(x, y + 1) - LUM(x, y - 1));
                jxx += gx * gx, jxy += gx * gy, jyy += gy * gy;
            }
#undef LUM
        /* The gradient's main direction, turned 90 degrees: the streaks'. */
        double grad = 0.5 * atan2(2.0 * jxy, jxx - jyy) * 57.29577951308232;
        double axis = fmod(grad + 90.0 + 360.0, 180.0);
        double tr = jxx + jyy, det = sqrt((jxx - jyy) * (jxx - jyy) + 4.0 * jxy * jxy);
        printf("axis=%.1f coherence=%.3f\n", axis, tr > 0.0 ? det / tr : 0.0);
        stbi_image_free(a);
        return 0;
    }
    if (argc == 6 && !strcmp(argv[1], "--outline")) return outline(argv[2], atoi(argv[3]), atoi(argv[4]), atoi(argv[5]));
    if (argc != 6) {
        fprintf(stderr, "usage: png_region A.png B.png CX CY R | png_region --red A.png X0 Y0 X1 Y1 | "
                        "png_region --axis A.png CX CY R | png_region --chroma A.png X0 Y0 X1 Y1 | "
                        "png_region --luma A.png X0 Y0 X1 Y1 | "
                        "png_region --outline A.png X0 X1 R\n");
        return 2;
    }
    int w, h, w2, h2;
    unsigned char *a = load(argv[1], &w, &h), *b = load(argv[2], &w2, &h2);
    if (!a || !b || w != w2 || h != h2) {
        if (a && b) fprintf(stderr, "png_region: sizes differ: %dx%d and %dx%d\n", w, h, w2, h2);
        stbi_image_free(a);
        stbi_image_free(b);
        return 2;
    }
    double cx = atof(argv[3]), cy = atof(argv[4]), r = atof(argv[5]);
    double sum_in = 0.0;
    long in = 0, in_off = 0, out = 0, out_off = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            double d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
            const unsigned char *p = a + 4 * ((size_t)y * w + x), *q = b + 4 * ((size_t)y * w + x);
            int d = diff(p, q);
            if (d2 <= r * r) {
                in++;
                in_off += d > 32;
                for (int c = 0; c < 3; c++) sum_in += abs((int)p[c] - (int)q[c]) / 3.0;
            } else if (d2 > 2.25 * r * r) {
                out++;
                out_off += d > 32;
            }
        }
    /* The shift of A's disc that best matches B. */
    int best_dx = 0, best_dy = 0;
    double best = INFINITY;
    for (int dy = -8; dy <= 8; dy++)
        for (int dx = -8; dx <= 8; dx++) {
            double sad = 0.0;
            long n = 0;
            for (int y = (int)(cy - r); y <= (int)(cy + r); y++)
                for (int x = (int)(cx - r); x <= (int)(cx + r); x++) {
                    if ((x - cx) * (x - cx) + (y - cy) * (y - cy) > r * r) continue;
                    int sx = x - dx, sy = y - dy;
                    if (x < 0 || y < 0 || x >= w || y >= h || sx < 0 || sy < 0 || sx >= w || sy >= h)
                        continue;
                    const unsigned char *p = a + 4 * ((size_t)sy * w + sx), *q = b + 4 * ((size_t)y * w + x);
                    for (int c = 0; c < 3; c++) sad += abs((int)p[c] - (int)q[c]);
                    n++;
                }
            if (n && sad / n < best) best = sad / n, best_dx = dx, best_dy = dy;
        }
    printf("inside_mean=%.2f inside_frac=%.4f outside_frac=%.5f shift_x=%d shift_y=%d\n",
           in ? sum_in / in : 0.0, in ? (double)in_off / in : 0.0, out ? (double)out_off / out : 0.0,
           best_dx, best_dy);
    stbi_image_free(a);
    stbi_image_free(b);
    return 0;
}
