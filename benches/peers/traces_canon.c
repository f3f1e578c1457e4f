/* The peer row for the canonical code: Traces (nauty 2.8.6) computing a canonical labelling
 * of a mesh read from an OFF file (faces only; the coordinates are skipped), timed alone
 * (the graph is built once, outside the timer). Two encodings, because Traces labels graphs
 * and a mesh is more than its graph:
 *
 *   skeleton  the mesh's vertices and edges (what the map's 1-skeleton says; for a quad
 *             torus it determines the map, in general it does not).
 *   darts     one vertex per dart (half-edge), with `next` as a directed path
 *             d - x_d - y_d - next(d) (x and y in their own colour cells, so the direction is
 *             kept) and the twin as an edge d - twin(d): the same information as the map,
 *             so its canonical labelling is an isomorphism invariant of the oriented map.
 *
 * Build and run (Debian: apt-get install libnauty2-dev):
 *   cc -O2 -o traces_canon benches/peers/traces_canon.c -lnauty
 *   cargo run --release --example workload -- 0 1 canonical /tmp/canon   (writes the OFF files)
 *   ./traces_canon /tmp/canon/torus_99856.off darts 5
 * Output: encoding, graph size, median and min seconds of REPS runs, group size. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "nauty/traces.h"

static double now(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

/* A half-edge: its key (origin << 32 | destination) and its index. */
typedef struct { unsigned long long key; int d; } half;

static int cmp_half(const void *a, const void *b) {
    unsigned long long x = ((const half *)a)->key, y = ((const half *)b)->key;
    return x < y ? -1 : x > y;
}

static int cmp_dbl(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The faces of an OFF file: corners (flat) and offsets (nf + 1). */
static void read_off(const char *path, int *nv, int *nf, int **corners, int **offsets) {
    FILE *f = fopen(path, "r");
    char tag[8];
    int ne;
    if (!f || fscanf(f, "%7s %d %d %d", tag, nv, nf, &ne) != 4 || strcmp(tag, "OFF")) {
        fprintf(stderr, "%s: not an OFF file with a count line\n", path);
        exit(2);
    }
    for (int i = 0; i < *nv; i++) {
        double x, y, z;
        if (fscanf(f, "%lf %lf %lf", &x, &y, &z) != 3) { fprintf(stderr, "bad vertex %d\n", i); exit(2); }
    }
    int cap = 4 * *nf + 16, n = 0;
    *corners = malloc(sizeof(int) * cap);
    *offsets = malloc(sizeof(int) * (*nf + 1));
    (*offsets)[0] = 0;
    for (int i = 0; i < *nf; i++) {
        int k;
        if (fscanf(f, "%d", &k) != 1 || k < 3) { fprintf(stderr, "bad face %d\n", i); exit(2); }
        if (n + k > cap) { cap = 2 * (n + k); *corners = realloc(*corners, sizeof(int) * cap); }
        for (int j = 0; j < k; j++)
            if (fscanf(f, "%d", &(*corners)[n++]) != 1) { fprintf(stderr, "bad face %d\n", i); exit(2); }
        (*offsets)[i + 1] = n;
    }
    fclose(f);
}

/* Fills a sparse graph from an adjacency given as (a, b) pairs, both directions added. */
static void fill(sparsegraph *g, int n, const int *ea, const int *eb, long m) {
    SG_ALLOC(*g, n, 2 * m, "fill");
    g->nv = n;
    g->nde = 2 * m;
    memset(g->d, 0, sizeof(int) * n);
    for (long i = 0; i < m; i++) { g->d[ea[i]]++; g->d[eb[i]]++; }
    size_t o = 0;
    for (int i = 0; i < n; i++) { g->v[i] = o; o += g->d[i]; g->d[i] = 0; }
    for (long i = 0; i < m; i++) {
        g->e[g->v[ea[i]] + g->d[ea[i]]++] = eb[i];
        g->e[g->v[eb[i]] + g->d[eb[i]]++] = ea[i];
    }
}

int main(int argc, char **argv) {
    if (argc < 3) { fprintf(stderr, "usage: %s FILE.off skeleton|darts [REPS]\n", argv[0]); return 2; }
    int reps = argc > 3 ? atoi(argv[3]) : 5, nv, nf, *c, *o;
    read_off(argv[1], &nv, &nf, &c, &o);
    int nd = o[nf], darts = !strcmp(argv[2], "darts");
    /* Each half-edge's key (origin << 32 | destination), sorted, to find twins and edges. */
    unsigned long long *key = malloc(sizeof *key * nd);
    int *next = malloc(sizeof(int) * nd);
    for (int f = 0; f < nf; f++)
        for (int i = o[f]; i < o[f + 1]; i++) {
            int j = i + 1 < o[f + 1] ? i + 1 : o[f];
            next[i] = j;
            key[i] = (unsigned long long)c[i] << 32 | (unsigned)c[j];
        }
    half *sorted = malloc(sizeof *sorted * nd);
    for (int d = 0; d < nd; d++) { sorted[d].key = key[d]; sorted[d].d = d; }
    qsort(sorted, nd, sizeof *sorted, cmp_half);
    int n = darts ? 3 * nd : nv;
    int *ea = malloc(sizeof(int) * 4 * nd), *eb = malloc(sizeof(int) * 4 * nd);
    long m = 0;
    for (int d = 0; d < nd; d++) {
        unsigned a = key[d] >> 32, b = (unsigned)key[d];
        half rev = {(unsigned long long)b << 32 | a, 0};
        const half *twin = bsearch(&rev, sorted, nd, sizeof *sorted, cmp_half);
        if (darts) {
            ea[m] = d; eb[m++] = nd + d;
            ea[m] = nd + d; eb[m++] = 2 * nd + d;
            ea[m] = 2 * nd + d; eb[m++] = next[d];
            if (twin && a < b) { ea[m] = d; eb[m++] = twin->d; }
        } else if (a < b || !twin) {
            ea[m] = a; eb[m++] = b;
        }
    }
    SG_DECL(g);
    SG_DECL(cg);
    fill(&g, n, ea, eb, m);
    int *lab = malloc(sizeof(int) * n), *ptn = malloc(sizeof(int) * n), *orbits = malloc(sizeof(int) * n);
    double *t = malloc(sizeof(double) * reps), grp1 = 0;
    int grp2 = 0;
    for (int r = 0; r < reps; r++) {
        for (int i = 0; i < n; i++) { lab[i] = i; ptn[i] = 1; }
        if (darts) { ptn[nd - 1] = 0; ptn[2 * nd - 1] = 0; }
        ptn[n - 1] = 0;
        DEFAULTOPTIONS_TRACES(opts);
        opts.getcanon = TRUE;
        opts.defaultptn = darts ? FALSE : TRUE;
        TracesStats stats;
        double t0 = now();
        Traces(&g, lab, ptn, orbits, &opts, &stats, &cg);
        t[r] = now() - t0;
        grp1 = stats.grpsize1;
        grp2 = stats.grpsize2;
    }
    double min = t[0];
    for (int r = 1; r < reps; r++) if (t[r] < min) min = t[r];
    qsort(t, reps, sizeof *t, cmp_dbl);
    printf("%s %s: %d graph vertices, %ld edges, %d faces; Traces canonical labelling median %.2f ms, min %.2f ms (%d runs); group %.3ge%d\n",
           argv[1], argv[2], n, m, nf, 1e3 * t[reps / 2], 1e3 * min, reps, grp1, grp2);
    return 0;
}
