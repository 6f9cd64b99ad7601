/*
 * compare-embree.c: Embree's single-ray API on the ray sets of `strahl bench`, printed as one
 * JSON line of the same shape, so the two can be compared side by side.
 *
 * What it does
 *   Loads the triangles of an OBJ file the way strahl does (polygons as fans from their first
 *   corner; triangles whose area, 0.5·|(p1−p0)×(p2−p0)| in single precision, is not positive are
 *   dropped), builds one Embree 3 scene over them (one device thread, build quality HIGH by
 *   default), and traces the ray set of `strahl bench SCENE --rays primary|random` one ray at a
 *   time with rtcIntersect1 (closest hit) and rtcOccluded1 (any hit), t ∈ [0, ∞), on the calling
 *   thread. Each query pass over all rays is repeated --repeat times (default 3, as strahl) and
 *   the fastest pass is reported, as strahl does. build_seconds is the wall-clock time from
 *   rtcNewScene (geometry creation and copying the vertex and index buffers included) to the end
 *   of rtcCommitScene; creating the device is not timed.
 *
 *   The ray sets are regenerated here with the operations strahl performs, in the same order and
 *   in single precision, so that they come out bit for bit equal (checked against rays dumped by
 *   strahl's own library code; see docs/PERFORMANCE.md):
 *   - primary: strahl's bare-mesh camera. The bounds of the kept triangles (from p0, p0+e1 and
 *     p0+e2, e = p − p0, as strahl stores them) give the centre c; the pinhole camera sits at c,
 *     looks at c + (1,0,0), up (0,1,0), 90° vertical field of view, 1024 × 1024 pixels, one unit
 *     direction through each pixel centre, traced in 16 × 16 tiles, row by row inside a tile
 *     (strahl's src/scene/camera.rs and src/cli/bench.rs);
 *   - random: 2^20 rays from one PCG32 stream (rand_pcg's Lcg64Xsh32, seeded as strahl's Sampler
 *     for seed 0x5eed, stream 0, sample 0); per ray five numbers u = (next_u32() >> 8)·2^-24:
 *     origin = min + (u0,u1,u2)·(max − min), direction uniform on the sphere (z = 1 − 2·u3,
 *     φ = 2π·u4) (src/sampling/sampler.rs and warp.rs).
 *   Compile without floating-point contraction (-ffp-contract=off): strahl's Rust code never fuses
 *   a multiply and an add, and a fused one would change the rays in their last bits.
 *
 * How to run
 *   gcc -O3 -march=native -ffp-contract=off -o compare-embree scripts/compare-embree.c -lembree3 -lm
 *   ./compare-embree SCENE.obj [--rays primary|random] [--quality high|medium|low] [--repeat N]
 *                    [--dump-rays FILE] [--dump-hits FILE] [--embree-config CFG] [--no-ftz]
 *   --dump-rays writes the rays in trace order as little-endian float32 (ox oy oz dx dy dz);
 *   --dump-hits writes the closest-hit t of each ray as float32 (inf for a miss). Both are for
 *   checking the ray sets, not part of the timing. --embree-config appends to the device
 *   configuration ("verbose=1" shows the BVH and kernels Embree picks). Flush-to-zero and
 *   denormals-are-zero are switched on before Embree is called, as Embree's documentation asks of
 *   every thread that uses it (--no-ftz leaves them off; strahl runs with them off).
 *   scripts/compare-embree.sh compiles this file and runs it alternately with `strahl bench`.
 *   Needs Embree 3 (Debian: apt-get install libembree-dev).
 *
 * Scene
 *   Written for the Grynberg & Ward conference room, conference.obj (331,179 triangles; public
 *   domain, from Morgan McGuire's Computer Graphics Archive, https://casual-effects.com/data/),
 *   which is not kept in this repository (the copy measured was converted to OBJ, geometry only,
 *   from conference.zip in github.com/taqu/BoundingVolumeHierarchy at 62fa086; see
 *   compare-embree.sh). Any OBJ whose faces are triangles or convex planar polygons gives the
 *   triangles strahl gives (strahl splits concave and bent polygons in its own way; a warning is
 *   printed when the file has faces with more than three corners).
 */
#include <embree3/rtcore.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <xmmintrin.h>

typedef struct { float x, y, z; } vec3;

static vec3 v3(float x, float y, float z) { vec3 v = {x, y, z}; return v; }
static vec3 add(vec3 a, vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static vec3 sub(vec3 a, vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static vec3 mul(vec3 a, vec3 b) { return v3(a.x * b.x, a.y * b.y, a.z * b.z); }
static vec3 scale(vec3 a, float s) { return v3(a.x * s, a.y * s, a.z * s); }
/* glam's order: (x·x + y·y) + z·z. */
static float dot(vec3 a, vec3 b) { return (a.x * b.x) + (a.y * b.y) + (a.z * b.z); }
static vec3 cross(vec3 a, vec3 b) {
    return v3(a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y);
}
/* glam's normalize: v · (1 / sqrt(v·v)). */
static vec3 normalize(vec3 a) { return scale(a, 1.0f / sqrtf(dot(a, a))); }
static vec3 vmin(vec3 a, vec3 b) { return v3(fminf(a.x, b.x), fminf(a.y, b.y), fminf(a.z, b.z)); }
static vec3 vmax(vec3 a, vec3 b) { return v3(fmaxf(a.x, b.x), fmaxf(a.y, b.y), fmaxf(a.z, b.z)); }

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void die(const char *msg, const char *arg) {
    fprintf(stderr, "compare-embree: %s%s\n", msg, arg ? arg : "");
    exit(1);
}

/* ---- OBJ: positions and faces only ---------------------------------------------------- */

typedef struct {
    vec3 *v;
    size_t nv, cap_v;
    uint32_t *tri; /* kept triangles, 3 indices each */
    size_t nt, cap_t;
    size_t faces, polygons, dropped;
} Mesh;

static void push_vertex(Mesh *m, vec3 p) {
    if (m->nv == m->cap_v) {
        m->cap_v = m->cap_v ? 2 * m->cap_v : 1 << 16;
        m->v = realloc(m->v, m->cap_v * sizeof *m->v);
        if (!m->v) die("out of memory", NULL);
    }
    m->v[m->nv++] = p;
}

/* Keeps triangle (a, b, c) unless its area is not positive, as strahl's Triangle::area. */
static void push_triangle(Mesh *m, uint32_t a, uint32_t b, uint32_t c) {
    vec3 p0 = m->v[a], e1 = sub(m->v[b], p0), e2 = sub(m->v[c], p0);
    vec3 n = cross(e1, e2);
    float area = 0.5f * sqrtf(dot(n, n));
    if (area <= 0.0f) {
        m->dropped++;
        return;
    }
    if (m->nt == m->cap_t) {
        m->cap_t = m->cap_t ? 2 * m->cap_t : 1 << 16;
        m->tri = realloc(m->tri, 3 * m->cap_t * sizeof *m->tri);
        if (!m->tri) die("out of memory", NULL);
    }
    m->tri[3 * m->nt] = a;
    m->tri[3 * m->nt + 1] = b;
    m->tri[3 * m->nt + 2] = c;
    m->nt++;
}

static void load_obj(const char *path, Mesh *m) {
    FILE *f = fopen(path, "r");
    if (!f) die("cannot open ", path);
    char line[65536];
    uint32_t *corner = NULL;
    size_t cap_corner = 0;
    while (fgets(line, sizeof line, f)) {
        char *s = line;
        while (*s == ' ' || *s == '\t') s++;
        if (s[0] == 'v' && (s[1] == ' ' || s[1] == '\t')) {
            char *end;
            vec3 p;
            p.x = strtof(s + 2, &end);
            p.y = strtof(end, &end);
            p.z = strtof(end, &end);
            push_vertex(m, p);
        } else if (s[0] == 'f' && (s[1] == ' ' || s[1] == '\t')) {
            size_t n = 0;
            char *t = s + 2;
            for (;;) {
                while (*t == ' ' || *t == '\t') t++;
                if (*t == '\0' || *t == '\n' || *t == '\r' || *t == '#') break;
                char *end;
                long i = strtol(t, &end, 10);
                if (end == t) die("bad face index on a line of ", path);
                long index = i > 0 ? i - 1 : (long)m->nv + i; /* negative: relative */
                if (index < 0 || (size_t)index >= m->nv) die("face index out of range in ", path);
                while (*end && *end != ' ' && *end != '\t' && *end != '\n' && *end != '\r') end++;
                t = end;
                if (n == cap_corner) {
                    cap_corner = cap_corner ? 2 * cap_corner : 16;
                    corner = realloc(corner, cap_corner * sizeof *corner);
                    if (!corner) die("out of memory", NULL);
                }
                corner[n++] = (uint32_t)index;
            }
            if (n < 3) continue;
            m->faces++;
            if (n > 3) m->polygons++;
            for (size_t k = 1; k + 1 < n; k++) push_triangle(m, corner[0], corner[k], corner[k + 1]);
        }
    }
    free(corner);
    fclose(f);
    if (m->polygons)
        fprintf(stderr,
                "compare-embree: warning: %zu faces have more than three corners; they are split "
                "as fans, which matches strahl only for convex planar faces\n",
                m->polygons);
}

/* Bounds of the kept triangles from the corners strahl stores: p0, p0 + e1, p0 + e2. */
static void bounds(const Mesh *m, vec3 *lo, vec3 *hi) {
    *lo = v3(INFINITY, INFINITY, INFINITY);
    *hi = v3(-INFINITY, -INFINITY, -INFINITY);
    for (size_t t = 0; t < m->nt; t++) {
        vec3 p0 = m->v[m->tri[3 * t]];
        vec3 p[3] = {p0, add(p0, sub(m->v[m->tri[3 * t + 1]], p0)),
                     add(p0, sub(m->v[m->tri[3 * t + 2]], p0))};
        for (int k = 0; k < 3; k++) {
            *lo = vmin(*lo, p[k]);
            *hi = vmax(*hi, p[k]);
        }
    }
}

/* ---- the ray sets of `strahl bench` --------------------------------------------------- */

typedef struct { vec3 o, d; } Ray;

#define PRIMARY_WIDTH 1024u
#define TILE 16u
#define RANDOM_RAYS (1u << 20)
#define PI_F 3.14159265358979323846f /* Rust's f32 PI: the float nearest π */

static Ray *primary_rays(vec3 lo, vec3 hi, size_t *count) {
    /* load_bare_mesh: camera at the centre of the bounds, 90° field of view, 1024 × 1024. */
    const uint32_t cam_w = 1024, cam_h = 1024;
    const float fov_degrees = 90.0f;
    vec3 position = scale(add(lo, hi), 0.5f);
    vec3 look_at = add(position, v3(1.0f, 0.0f, 0.0f));
    vec3 up_hint = v3(0.0f, 1.0f, 0.0f);
    /* Camera::rays */
    vec3 forward = normalize(sub(look_at, position));
    vec3 right = normalize(cross(forward, up_hint));
    vec3 up = cross(right, forward);
    uint32_t width = PRIMARY_WIDTH;
    uint32_t height = (uint32_t)roundf((float)PRIMARY_WIDTH * (float)cam_h / (float)cam_w);
    if (height < 1) height = 1;
    const float rads_per_deg = PI_F / 180.0f;
    float half_h = tanf(fov_degrees * rads_per_deg * 0.5f);
    float half_w = half_h * (float)width / (float)height;
    vec3 dx = scale(right, 2.0f * half_w / (float)width);
    vec3 dy = scale(up, -2.0f * half_h / (float)height);
    vec3 corner = add(sub(forward, scale(right, half_w)), scale(up, half_h));
    /* bench.rs: 16 × 16 tiles, row-major over tiles, row-major inside a tile. */
    Ray *rays = malloc((size_t)width * height * sizeof *rays);
    if (!rays) die("out of memory", NULL);
    size_t n = 0;
    uint32_t tiles_x = (width + TILE - 1) / TILE, tiles_y = (height + TILE - 1) / TILE;
    for (uint32_t tile = 0; tile < tiles_x * tiles_y; tile++) {
        uint32_t x0 = tile % tiles_x * TILE, y0 = tile / tiles_x * TILE;
        for (uint32_t y = y0; y < y0 + TILE && y < height; y++)
            for (uint32_t x = x0; x < x0 + TILE && x < width; x++) {
                float px = (float)x + 0.5f, py = (float)y + 0.5f;
                vec3 d = normalize(add(add(corner, scale(dx, px)), scale(dy, py)));
                rays[n].o = position;
                rays[n].d = d;
                n++;
            }
    }
    *count = n;
    return rays;
}

/* SplitMix64 finaliser (strahl's hash64). */
static uint64_t hash64(uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

/* rand_pcg 0.10 Lcg64Xsh32 (PCG32, XSH RR). */
typedef struct { uint64_t state, inc; } Pcg32;
#define PCG_MULT 6364136223846793005ull
static Pcg32 pcg32_new(uint64_t state, uint64_t stream) {
    Pcg32 r;
    r.inc = (stream << 1) | 1;
    r.state = state + r.inc;
    r.state = r.state * PCG_MULT + r.inc;
    return r;
}
static uint32_t pcg32_next(Pcg32 *r) {
    uint64_t s = r->state;
    r->state = s * PCG_MULT + r->inc;
    uint32_t rot = (uint32_t)(s >> 59);
    uint32_t xsh = (uint32_t)(((s >> 18) ^ s) >> 27);
    return (xsh >> rot) | (xsh << ((32 - rot) & 31));
}
static float next_1d(Pcg32 *r) { return (float)(pcg32_next(r) >> 8) * (1.0f / 16777216.0f); }

static Ray *random_rays(vec3 lo, vec3 hi, size_t *count) {
    /* Sampler::new(SequenceKind::Random, 0x5eed, 0, 0) */
    const uint64_t seed = 0x5eed, stream = 0, sample_index = 0;
    uint64_t pixel_key = hash64(seed ^ hash64(stream));
    uint64_t state = hash64(pixel_key ^ (sample_index * 0x2545f4914f6cdd1dull));
    Pcg32 rng = pcg32_new(state, pixel_key | 1);
    vec3 extent = sub(hi, lo);
    Ray *rays = malloc((size_t)RANDOM_RAYS * sizeof *rays);
    if (!rays) die("out of memory", NULL);
    for (size_t i = 0; i < RANDOM_RAYS; i++) {
        float ux = next_1d(&rng), uy = next_1d(&rng), uz = next_1d(&rng);
        rays[i].o = add(lo, mul(v3(ux, uy, uz), extent));
        /* warp::uniform_sphere */
        float a = next_1d(&rng), b = next_1d(&rng);
        float z = 1.0f - 2.0f * a;
        float r = sqrtf(fmaxf(1.0f - z * z, 0.0f));
        float phi = 2.0f * PI_F * b;
        rays[i].d = v3(r * cosf(phi), r * sinf(phi), z);
    }
    *count = RANDOM_RAYS;
    return rays;
}

/* ---- Embree ---------------------------------------------------------------------------- */

static void error_handler(void *user, enum RTCError code, const char *str) {
    (void)user;
    fprintf(stderr, "compare-embree: Embree error %d: %s\n", (int)code, str ? str : "");
    exit(1);
}

typedef struct {
    double seconds, mrays;
    size_t hits;
} Query;

static void init_rayhit(struct RTCRayHit *rh, const Ray *r) {
    rh->ray.org_x = r->o.x;
    rh->ray.org_y = r->o.y;
    rh->ray.org_z = r->o.z;
    rh->ray.tnear = 0.0f;
    rh->ray.dir_x = r->d.x;
    rh->ray.dir_y = r->d.y;
    rh->ray.dir_z = r->d.z;
    rh->ray.time = 0.0f;
    rh->ray.tfar = INFINITY;
    rh->ray.mask = 0xffffffffu;
    rh->ray.id = 0;
    rh->ray.flags = 0;
    rh->hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

static Query closest(RTCScene scene, const Ray *rays, size_t n, int repeat) {
    Query q = {INFINITY, 0, 0};
    for (int pass = 0; pass < repeat; pass++) {
        struct RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        size_t hits = 0;
        double start = now();
        for (size_t i = 0; i < n; i++) {
            struct RTCRayHit rh;
            init_rayhit(&rh, &rays[i]);
            rtcIntersect1(scene, &ctx, &rh);
            hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
        double s = now() - start;
        if (s < q.seconds) q.seconds = s;
        q.hits = hits;
    }
    q.mrays = n / q.seconds / 1e6;
    return q;
}

static Query any(RTCScene scene, const Ray *rays, size_t n, int repeat) {
    Query q = {INFINITY, 0, 0};
    for (int pass = 0; pass < repeat; pass++) {
        struct RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        size_t hits = 0;
        double start = now();
        for (size_t i = 0; i < n; i++) {
            struct RTCRay ray;
            ray.org_x = rays[i].o.x;
            ray.org_y = rays[i].o.y;
            ray.org_z = rays[i].o.z;
            ray.tnear = 0.0f;
            ray.dir_x = rays[i].d.x;
            ray.dir_y = rays[i].d.y;
            ray.dir_z = rays[i].d.z;
            ray.time = 0.0f;
            ray.tfar = INFINITY;
            ray.mask = 0xffffffffu;
            ray.id = 0;
            ray.flags = 0;
            rtcOccluded1(scene, &ctx, &ray);
            hits += ray.tfar == -INFINITY;
        }
        double s = now() - start;
        if (s < q.seconds) q.seconds = s;
        q.hits = hits;
    }
    q.mrays = n / q.seconds / 1e6;
    return q;
}

static void json_string(const char *s) {
    putchar('"');
    for (; *s; s++) {
        if (*s == '"' || *s == '\\') putchar('\\');
        putchar(*s);
    }
    putchar('"');
}

int main(int argc, char **argv) {
    const char *scene_path = NULL, *set = "primary", *quality = "high";
    const char *dump_rays = NULL, *dump_hits = NULL, *extra_config = NULL;
    int repeat = 3, ftz = 1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *next = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "--rays") && next) set = argv[++i];
        else if (!strcmp(a, "--quality") && next) quality = argv[++i];
        else if (!strcmp(a, "--repeat") && next) repeat = atoi(argv[++i]);
        else if (!strcmp(a, "--dump-rays") && next) dump_rays = argv[++i];
        else if (!strcmp(a, "--dump-hits") && next) dump_hits = argv[++i];
        else if (!strcmp(a, "--embree-config") && next) extra_config = argv[++i];
        else if (!strcmp(a, "--no-ftz")) ftz = 0;
        else if (a[0] != '-' && !scene_path) scene_path = a;
        else die("usage: compare-embree SCENE.obj [--rays primary|random] [--quality high|medium|low] "
                 "[--repeat N] [--dump-rays FILE] [--dump-hits FILE] [--embree-config CFG] [--no-ftz]; "
                 "bad argument ", a);
    }
    if (!scene_path) die("no scene given (an .obj file)", NULL);
    if (repeat < 1) die("--repeat must be at least 1", NULL);
    enum RTCBuildQuality q;
    if (!strcmp(quality, "high")) q = RTC_BUILD_QUALITY_HIGH;
    else if (!strcmp(quality, "medium")) q = RTC_BUILD_QUALITY_MEDIUM;
    else if (!strcmp(quality, "low")) q = RTC_BUILD_QUALITY_LOW;
    else die("--quality must be high, medium or low, not ", quality);

    Mesh mesh = {0};
    load_obj(scene_path, &mesh);
    if (mesh.nt == 0) die("the mesh has no faces with area: ", scene_path);
    vec3 lo, hi;
    bounds(&mesh, &lo, &hi);

    size_t n;
    Ray *rays;
    if (!strcmp(set, "primary")) rays = primary_rays(lo, hi, &n);
    else if (!strcmp(set, "random")) rays = random_rays(lo, hi, &n);
    else die("--rays must be primary or random, not ", set);

    /* Embree's documented set-up: flush denormals to zero on every thread that calls it (after
       the rays are made, so they are not affected). */
    if (ftz) _mm_setcsr(_mm_getcsr() | 0x8040); /* FTZ (bit 15) and DAZ (bit 6) */

    /* One thread: the build runs on the calling thread only; tracing is on this thread. */
    char config[512];
    snprintf(config, sizeof config, "threads=1,set_affinity=0%s%s", extra_config ? "," : "",
             extra_config ? extra_config : "");
    RTCDevice device = rtcNewDevice(config);
    if (!device) die("cannot create an Embree device", NULL);
    rtcSetDeviceErrorFunction(device, error_handler, NULL);

    double start = now();
    RTCScene scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, q);
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_NONE);
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geom, q);
    float *vb = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), mesh.nv);
    memcpy(vb, mesh.v, mesh.nv * sizeof(vec3));
    uint32_t *ib = rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                           3 * sizeof(uint32_t), mesh.nt);
    memcpy(ib, mesh.tri, mesh.nt * 3 * sizeof(uint32_t));
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(scene);
    double build = now() - start;

    Query c = closest(scene, rays, n, repeat);
    Query a = any(scene, rays, n, repeat);

    /* Untimed checksum pass (and the optional dumps): sum of closest-hit distances. */
    double t_sum = 0.0;
    FILE *fr = dump_rays ? fopen(dump_rays, "wb") : NULL;
    FILE *fh = dump_hits ? fopen(dump_hits, "wb") : NULL;
    if ((dump_rays && !fr) || (dump_hits && !fh)) die("cannot write a dump file", NULL);
    {
        struct RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        for (size_t i = 0; i < n; i++) {
            struct RTCRayHit rh;
            init_rayhit(&rh, &rays[i]);
            rtcIntersect1(scene, &ctx, &rh);
            float t = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID ? rh.ray.tfar : INFINITY;
            if (isfinite(t)) t_sum += t;
            if (fr) {
                float r6[6] = {rays[i].o.x, rays[i].o.y, rays[i].o.z,
                               rays[i].d.x, rays[i].d.y, rays[i].d.z};
                fwrite(r6, sizeof r6, 1, fr);
            }
            if (fh) fwrite(&t, sizeof t, 1, fh);
        }
    }
    if (fr) fclose(fr);
    if (fh) fclose(fh);

    printf("{\"scene\":");
    json_string(scene_path);
    printf(",\"accel\":\"embree-%s\",\"threads\":1,\"rays\":\"%s\",\"ray_count\":%zu,"
           "\"primitives\":%zu,\"build_seconds\":%.9f,"
           "\"closest_hit\":{\"seconds\":%.9f,\"mrays_per_second\":%.6f,\"hits\":%zu},"
           "\"any_hit\":{\"seconds\":%.9f,\"mrays_per_second\":%.6f,\"hits\":%zu},"
           "\"closest_t_sum\":%.6f,\"embree_version\":\"%ld.%ld.%ld\",\"faces\":%zu,"
           "\"zero_area_dropped\":%zu,\"ftz_daz\":%s}\n",
           quality, set, n, mesh.nt, build, c.seconds, c.mrays, c.hits, a.seconds, a.mrays, a.hits,
           t_sum, (long)rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION_MAJOR),
           (long)rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION_MINOR),
           (long)rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION_PATCH), mesh.faces,
           mesh.dropped, ftz ? "true" : "false");

    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    free(rays);
    free(mesh.v);
    free(mesh.tri);
    return 0;
}
