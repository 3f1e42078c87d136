/* The display mapping's fits (pelt__display, core/fur/shading.c;
 * display_color, gl/shaders/shading.glsl): for each tone curve, the sRGB
 * encoding of the curve as one rational function of s = sqrt(v), v the
 * exposed linear value,
 *
 *   P(s) / Q(s),  P = p1 s + ... + pm s^m,  Q = 1 + q1 s + ... + qn s^n,
 *
 * over 0 <= v <= v_max, where the curve reaches white. Fitted by linear
 * least squares on P - g Q, reweighted by 1 / Q^2 of the last round
 * (Loeb's iteration, which makes the residual P / Q - g's), and from the
 * 20th round on by Lawson's weights, which grow where the error is largest
 * and so draw the fit towards the least maximum error; the best round is
 * kept. Prints each curve's ten numbers (p1..p5, q1..q4, v_max) and its
 * worst error in 1/255ths, checked on a finer grid than the fit's.
 *
 *   cc -O2 scripts/display_fit.c -lm -o /tmp/display_fit && /tmp/display_fit
 */
#include <math.h>
#include <stdio.h>

#define SAMPLES 4000
#define ROUNDS 400
#define MAX_TERMS 9

static double srgb_encode(double l)
{
    l = fmin(fmax(l, 0.0), 1.0);
    return l <= 0.0031308 ? 12.92 * l : 1.055 * pow(l, 1.0 / 2.4) - 0.055;
}

/* Narkowicz's ACES fit, its input scaled by 0.6 (pelt__tone). */
static double tone(double v, int curve)
{
    if (curve == 1) return fmin(v, 1.0);
    double x = 0.6 * v;
    return fmin(fmax(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0), 1.0);
}

static double target(double s, int curve) { return srgb_encode(tone(s * s, curve)); }

typedef struct {
    int m, n; /* P's and Q's degrees */
    double c[MAX_TERMS];
} fit;

static double eval(const fit *f, double s, double *q_out)
{
    double p = 0.0, q = 1.0, pw = s;
    for (int i = 0; i < f->m; i++, pw *= s) p += f->c[i] * pw;
    pw = s;
    for (int i = 0; i < f->n; i++, pw *= s) q += f->c[f->m + i] * pw;
    if (q_out) *q_out = q;
    return p / q;
}

/* Solves A x = b in place (b becomes x) by elimination with partial pivots. */
static void solve(int n, double a[MAX_TERMS][MAX_TERMS], double b[MAX_TERMS])
{
    for (int i = 0; i < n; i++) {
        int pivot = i;
        for (int r = i + 1; r < n; r++)
            if (fabs(a[r][i]) > fabs(a[pivot][i])) pivot = r;
        for (int k = 0; k < n; k++) {
            double t = a[i][k];
            a[i][k] = a[pivot][k];
            a[pivot][k] = t;
        }
        double t = b[i];
        b[i] = b[pivot];
        b[pivot] = t;
        for (int r = 0; r < n; r++) {
            if (r == i) continue;
            double f = a[r][i] / a[i][i];
            for (int k = i; k < n; k++) a[r][k] -= f * a[i][k];
            b[r] -= f * b[i];
        }
    }
    for (int i = 0; i < n; i++) b[i] /= a[i][i];
}

static double fit_curve(int curve, double v_max, fit *best)
{
    static double s[SAMPLES], loeb[SAMPLES], lawson[SAMPLES];
    const double s_max = sqrt(v_max);
    const int terms = best->m + best->n;
    for (int k = 0; k < SAMPLES; k++) {
        double u = (double)k / (SAMPLES - 1);
        s[k] = s_max * 0.5 * (u + u * u); /* denser towards black */
        loeb[k] = lawson[k] = 1.0;
    }
    double best_error = INFINITY;
    fit f = *best;
    for (int round = 0; round < ROUNDS; round++) {
        double a[MAX_TERMS][MAX_TERMS] = {{0}}, b[MAX_TERMS] = {0};
        for (int k = 0; k < SAMPLES; k++) {
            double row[MAX_TERMS], g = target(s[k], curve), pw = s[k], w = loeb[k] * lawson[k];
            for (int i = 0; i < f.m; i++, pw *= s[k]) row[i] = pw;
            pw = s[k];
            for (int i = 0; i < f.n; i++, pw *= s[k]) row[f.m + i] = -g * pw;
            for (int i = 0; i < terms; i++) {
                b[i] += w * row[i] * g;
                for (int j = 0; j < terms; j++) a[i][j] += w * row[i] * row[j];
            }
        }
        solve(terms, a, b);
        for (int i = 0; i < terms; i++) f.c[i] = b[i];
        double worst = 0.0, least_q = INFINITY;
        for (int k = 0; k < SAMPLES; k++) {
            double q, e = fabs(eval(&f, s[k], &q) - target(s[k], curve));
            loeb[k] = 1.0 / (q * q);
            worst = fmax(worst, e);
            least_q = fmin(least_q, q);
        }
        if (round >= 20) {
            double sum = 0.0;
            for (int k = 0; k < SAMPLES; k++) {
                double e = fabs(eval(&f, s[k], NULL) - target(s[k], curve));
                lawson[k] *= pow(e / worst + 1e-3, 0.3);
                sum += lawson[k];
            }
            for (int k = 0; k < SAMPLES; k++) lawson[k] *= SAMPLES / sum;
        }
        if (least_q > 0.05 && worst < best_error) { /* no pole near the range */
            best_error = worst;
            *best = f;
        }
    }
    /* The worst error as the renderer uses it: clamped, over decades of v. */
    double worst = 0.0;
    for (int i = 0; i <= 200000; i++) {
        double v = pow(10.0, -6.0 + 8.0 * i / 200000), ss = sqrt(fmin(v, v_max));
        double r = fmin(fmax(eval(best, ss, NULL), 0.0), 1.0);
        worst = fmax(worst, fabs(r - target(ss, curve)));
    }
    return worst;
}

int main(void)
{
    /* The filmic curve reaches 1 where 0.08 x^2 - 0.56 x - 0.14 = 0. */
    const double filmic_max = (0.56 + sqrt(0.56 * 0.56 + 4.0 * 0.08 * 0.14)) / 0.16 / 0.6;
    const struct {
        const char *name;
        int m, n;
        double v_max;
    } curves[2] = {{"filmic", 5, 4, filmic_max}, {"none", 3, 3, 1.0}};
    for (int curve = 0; curve < 2; curve++) {
        fit f = {curves[curve].m, curves[curve].n, {0}};
        double worst = fit_curve(curve, curves[curve].v_max, &f);
        double p[5] = {0}, q[4] = {0};
        for (int i = 0; i < f.m; i++) p[i] = f.c[i];
        for (int i = 0; i < f.n; i++) q[i] = f.c[f.m + i];
        printf("%s (within %.3f / 255):\n  {%.9g, %.9g, %.9g, %.9g, %.9g, %.9g, %.9g, %.9g, %.9g, %.6g}\n",
               curves[curve].name, 255.0 * worst, p[0], p[1], p[2], p[3], p[4], q[0], q[1], q[2], q[3],
               curves[curve].v_max);
    }
    return 0;
}
