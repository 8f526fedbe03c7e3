/*
 * Adaptive cubature: tensor-product Gauss-Kronrod (G7/K15) rules on
 * rectangles, refined globally where the error is largest (the strategy of
 * QUADPACK's qag, in two dimensions). The K15 nodes contain the G7 nodes, so
 * one 15 x 15 evaluation gives the K15xK15 estimate, and the G7xK15 and
 * K15xG7 estimates whose differences tell which axis to split.
 */
#include <string.h>
#include "materia/tools/cubature.h"
#include "core/alloc.h"

/* The 15 Kronrod nodes of [-1, 1] in order, their weights, and the weights of
 * the embedded 7-point Gauss rule (zero at the nodes it does not use): the
 * standard QUADPACK qk15 constants. */
#define K1 0.991455371120812639206854697526329
#define K2 0.949107912342758524526189684047851
#define K3 0.864864423359769072789712788640926
#define K4 0.741531185599394439863864773280788
#define K5 0.586087235467691130294144845693013
#define K6 0.405845151377397166906606412076961
#define K7 0.207784955007898467600689403773245
#define W1 0.022935322010529224963732008058970
#define W2 0.063092092629978553290700663189204
#define W3 0.104790010322250183839876322541518
#define W4 0.140653259715525918745189590510238
#define W5 0.169004726639267902826583426598550
#define W6 0.190350578064785409913256402421014
#define W7 0.204432940075298892414161999234649
#define W8 0.209482141084727828012999174891714
#define G2 0.129484966168869693270611432679082
#define G4 0.279705391489276667901467771423780
#define G6 0.381830050505118944950369775488975
#define G8 0.417959183673469387755102040816327
static const double node[15] = {-K1, -K2, -K3, -K4, -K5, -K6, -K7, 0, K7, K6, K5, K4, K3, K2, K1};
static const double wk[15] = {W1, W2, W3, W4, W5, W6, W7, W8, W7, W6, W5, W4, W3, W2, W1};
static const double wgs[15] = {0, G2, 0, G4, 0, G6, 0, G8, 0, G6, 0, G4, 0, G2, 0};

typedef struct region {
    double x0, x1, y0, y1;
    double value[MT_CUBATURE_MAX_COMPONENTS];
    double error[MT_CUBATURE_MAX_COMPONENTS];
    int split_x; /* the x axis carries more of the error */
    double priority;
} region;

typedef struct cub {
    mt_cubature_fn f;
    void *ctx;
    int ncomp;
    double buf[15 * 15 * MT_CUBATURE_MAX_COMPONENTS];
} cub;

static void evaluate(cub *c, region *r)
{
    double cx = 0.5 * (r->x0 + r->x1), hx = 0.5 * (r->x1 - r->x0);
    double cy = 0.5 * (r->y0 + r->y1), hy = 0.5 * (r->y1 - r->y0);
    double ex[MT_CUBATURE_MAX_COMPONENTS] = {0}, ey[MT_CUBATURE_MAX_COMPONENTS] = {0};
    double sex = 0, sey = 0;
    int i, j, k, n = c->ncomp;
    for (i = 0; i < 15; ++i)
        for (j = 0; j < 15; ++j) c->f(c->ctx, cx + hx * node[i], cy + hy * node[j], c->buf + (i * 15 + j) * n);
    for (k = 0; k < n; ++k) {
        double kk = 0, gk = 0, kg = 0;
        for (i = 0; i < 15; ++i)
            for (j = 0; j < 15; ++j) {
                double v = c->buf[(i * 15 + j) * n + k];
                kk += wk[i] * wk[j] * v;
                gk += wgs[i] * wk[j] * v;
                kg += wk[i] * wgs[j] * v;
            }
        r->value[k] = kk * hx * hy;
        ex[k] = fabs(kk - gk) * hx * hy;
        ey[k] = fabs(kk - kg) * hx * hy;
        r->error[k] = ex[k] + ey[k];
        sex += ex[k];
        sey += ey[k];
    }
    r->split_x = sex >= sey;
}

/* Max-heap of regions by priority. */
static void heap_push(region *h, int *n, region r)
{
    int i = (*n)++;
    while (i > 0 && h[(i - 1) / 2].priority < r.priority) {
        h[i] = h[(i - 1) / 2];
        i = (i - 1) / 2;
    }
    h[i] = r;
}

static region heap_pop(region *h, int *n)
{
    region top = h[0], last = h[--*n];
    int i = 0;
    for (;;) {
        int c = 2 * i + 1;
        if (c >= *n) break;
        if (c + 1 < *n && h[c + 1].priority > h[c].priority) c++;
        if (h[c].priority <= last.priority) break;
        h[i] = h[c];
        i = c;
    }
    if (*n > 0) h[i] = last;
    return top;
}

static double priority(const region *r, const double *tol, int n)
{
    double p = 0;
    int k;
    for (k = 0; k < n; ++k) {
        double q = r->error[k] / tol[k];
        if (q > p) p = q;
    }
    return p;
}

mt_status mt_cubature(mt_cubature_fn f, void *ctx, int ncomp, double x0, double x1, double y0,
                      double y1, int nx, int ny, double rel_tol, double abs_tol, long max_evals,
                      mt_cubature_result *res, mt_error *err)
{
    cub *c;
    region *heap;
    int cap, n = 0, i, j, k;
    double tol[MT_CUBATURE_MAX_COMPONENTS];
    mt_error_clear(err);
    memset(res, 0, sizeof *res);
    if (ncomp < 1 || ncomp > MT_CUBATURE_MAX_COMPONENTS || nx < 1 || ny < 1 || !(x1 >= x0) ||
        !(y1 >= y0) || !(abs_tol > 0 || rel_tol > 0))
        return mt_error_set(err, MT_ERR_INVALID, "cubature: invalid arguments");
    if ((long)nx * ny > 1000000) return mt_error_set(err, MT_ERR_INVALID, "cubature: grid too fine");
    cap = nx * ny + 64;
    c = mt__malloc(sizeof *c);
    heap = mt__malloc((size_t)cap * sizeof *heap);
    if (!c || !heap) {
        mt__free(c);
        mt__free(heap);
        return mt_error_set(err, MT_ERR_NOMEM, "cubature: out of memory");
    }
    c->f = f;
    c->ctx = ctx;
    c->ncomp = ncomp;
    for (i = 0; i < nx; ++i)
        for (j = 0; j < ny; ++j) {
            region r;
            r.x0 = x0 + (x1 - x0) * i / nx;
            r.x1 = i + 1 == nx ? x1 : x0 + (x1 - x0) * (i + 1) / nx;
            r.y0 = y0 + (y1 - y0) * j / ny;
            r.y1 = j + 1 == ny ? y1 : y0 + (y1 - y0) * (j + 1) / ny;
            evaluate(c, &r);
            r.priority = 0;
            heap[n++] = r;
            for (k = 0; k < ncomp; ++k) {
                res->value[k] += r.value[k];
                res->error[k] += r.error[k];
            }
        }
    res->evaluations = 225L * nx * ny;
    for (;;) {
        region r, a, b;
        int done = 1;
        for (k = 0; k < ncomp; ++k) {
            tol[k] = fmax(abs_tol, rel_tol * fabs(res->value[k]));
            if (res->error[k] > tol[k]) done = 0;
        }
        if (done) {
            res->converged = 1;
            break;
        }
        if (res->evaluations + 450 > max_evals) break;
        if (res->evaluations <= 225L * nx * ny) {
            /* tolerances are known now: order the initial regions */
            int m = n;
            n = 0;
            for (i = 0; i < m; ++i) {
                region t = heap[i];
                t.priority = priority(&t, tol, ncomp);
                heap_push(heap, &n, t);
            }
        }
        r = heap_pop(heap, &n);
        a = b = r;
        if (r.split_x)
            a.x1 = b.x0 = 0.5 * (r.x0 + r.x1);
        else
            a.y1 = b.y0 = 0.5 * (r.y0 + r.y1);
        evaluate(c, &a);
        evaluate(c, &b);
        res->evaluations += 450;
        for (k = 0; k < ncomp; ++k) {
            res->value[k] += a.value[k] + b.value[k] - r.value[k];
            res->error[k] += a.error[k] + b.error[k] - r.error[k];
        }
        a.priority = priority(&a, tol, ncomp);
        b.priority = priority(&b, tol, ncomp);
        if (n + 2 > cap) {
            region *h = mt__realloc(heap, (size_t)(cap * 2) * sizeof *heap);
            if (!h) {
                mt__free(c);
                mt__free(heap);
                return mt_error_set(err, MT_ERR_NOMEM, "cubature: out of memory");
            }
            heap = h;
            cap *= 2;
        }
        heap_push(heap, &n, a);
        heap_push(heap, &n, b);
    }
    /* The running error sums drift with cancellation; recompute them. */
    for (k = 0; k < ncomp; ++k) {
        double v = 0, e = 0;
        for (i = 0; i < n; ++i) {
            v += heap[i].value[k];
            e += heap[i].error[k];
        }
        res->value[k] = v;
        res->error[k] = e;
    }
    mt__free(c);
    mt__free(heap);
    return MT_OK;
}

int mt_cubature_grid(double ratio)
{
    return ratio > 16 ? 8 : ratio > 4 ? 4 : ratio > 1.5 ? 2 : 1;
}

mt_vec3 mt_sphere_direction(double phi, double z)
{
    double r = sqrt(fmax(0.0, 1 - z * z));
    return mt_v3((mt_real)(r * cos(phi)), (mt_real)(r * sin(phi)), (mt_real)z);
}
