/* pelt's own checks of a mesh file before assimp reads it (pelt_mesh_load,
 * pelt_mesh_load_memory). assimp trusts what a file declares: it reserves
 * declared counts, reads past short buffers, leaks or aborts on malformed
 * text (docs/testing.md, Fuzzing, lists what each check keeps away). So
 * OFF, PLY, STL, OBJ and glTF/GLB are read here first, strictly: a file
 * passes only when it holds exactly what it declares, in the words and
 * numbers assimp reads the same way, and never a silently partial mesh. */
#include "core/mesh/mesh_internal.h"

#include "core/base/error.h"
#include "core/base/hooks.h"

#include <ctype.h>
#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* A NUL-terminated copy of (the first bytes of) the file. */
typedef struct text_reader {
    const char *s;
    size_t pos, len;
} text_reader;

static int ends_with_ci(const char *s, const char *suffix)
{
    size_t a = strlen(s), b = strlen(suffix);
    if (b > a) return 0;
    for (size_t i = 0; i < b; i++)
        if (tolower((unsigned char)s[a - b + i]) != tolower((unsigned char)suffix[i])) return 0;
    return 1;
}

/* Next whitespace-separated token into tok (truncated to cap - 1 chars);
 * returns 0 at the end. Stops at a newline when stop_at_newline. */
static int next_token(text_reader *r, char *tok, size_t cap, int stop_at_newline)
{
    while (r->pos < r->len && isspace((unsigned char)r->s[r->pos])) {
        if (stop_at_newline && r->s[r->pos] == '\n') return 0;
        r->pos++;
    }
    size_t n = 0;
    while (r->pos < r->len && !isspace((unsigned char)r->s[r->pos])) {
        if (n + 1 < cap) tok[n++] = r->s[r->pos];
        r->pos++;
    }
    tok[n] = '\0';
    return n > 0;
}

static void skip_line(text_reader *r)
{
    while (r->pos < r->len && r->s[r->pos] != '\n') r->pos++;
    if (r->pos < r->len) r->pos++;
}

/* Parses a decimal count; -1 when tok is not a plain non-negative integer.
 * Values beyond 2^62 saturate (they fail the size checks all the same). */
static long long parse_count(const char *tok)
{
    if (!isdigit((unsigned char)tok[0])) return -1;
    long long v = 0;
    for (const char *p = tok; *p; p++) {
        if (!isdigit((unsigned char)*p)) return -1;
        if (v < (1LL << 62) / 10) v = v * 10 + (*p - '0');
        else v = 1LL << 62;
    }
    return v;
}

/* [+-] digits. */
static int is_integer(const char *t)
{
    if (*t == '+' || *t == '-') t++;
    if (!isdigit((unsigned char)*t)) return 0;
    while (isdigit((unsigned char)*t)) t++;
    return *t == '\0';
}

/* A decimal number as assimp reads one: [+-] digits [. digits] [e [+-]
 * digits], or nan / inf. strtod also takes hexadecimal ("0x.58"), which
 * assimp reads differently (and then leaked). */
static int is_decimal(const char *t)
{
    if (*t == '+' || *t == '-') t++;
    if (!strcasecmp(t, "nan") || !strcasecmp(t, "inf") || !strcasecmp(t, "infinity")) return 1;
    int digits = 0;
    while (isdigit((unsigned char)*t)) t++, digits++;
    if (*t == '.') t++;
    while (isdigit((unsigned char)*t)) t++, digits++;
    if (!digits) return 0;
    if (*t == 'e' || *t == 'E') {
        t++;
        if (*t == '+' || *t == '-') t++;
        if (!isdigit((unsigned char)*t)) return 0;
        while (isdigit((unsigned char)*t)) t++;
    }
    return *t == '\0';
}

/* OFF line reader: skips blank lines and '#' comments, returns 1 with pos
 * at the start of the next content line (line number in *line). */
static int next_content_line(text_reader *r, long long *line, int hash_comments)
{
    while (r->pos < r->len) {
        size_t p = r->pos;
        while (p < r->len && r->s[p] != '\n' && isspace((unsigned char)r->s[p])) p++;
        if (p < r->len && r->s[p] != '\n' && (!hash_comments || r->s[p] != '#')) {
            (*line)++;
            return 1;
        }
        skip_line(r);
        (*line)++;
    }
    return 0;
}

static int off_next_line(text_reader *r, long long *line)
{
    return next_content_line(r, line, 1);
}

/* OFF is checked in full: assimp clamps out-of-range face indices and reads
 * "-1" as vertex 0, which would turn a corrupt file into a plausible mesh;
 * and it reserves the declared counts before reading, so a header claiming
 * two billion vertices must not reach it. */
/* 1 for an OFF header assimp reads ([ST][C][N]OFF), 2 for its 4D and n-D
 * variants, 0 for anything else. */
static int off_header(const char *t)
{
    int variant = 0;
    if (!strncmp(t, "ST", 2)) t += 2;
    if (*t == 'C') t++;
    if (*t == 'N') t++;
    if (*t == '4') t++, variant = 1;
    if (*t == 'n') t++, variant = 1;
    return !ends_with_ci(t, "OFF") || strlen(t) != 3 ? 0 : variant ? 2 : 1;
}

static pelt_status check_off(const char *path, text_reader *r, long long size, pelt_error *err)
{
    char tok[64];
    long long line = 0;
    if (!off_next_line(r, &line) || !next_token(r, tok, sizeof tok, 1))
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: OFF file holds nothing", path);
    /* assimp's rule: [ST][C][N][4][n]OFF is a header; a file without one
     * starts with its counts, and assimp then reads them one place on, so
     * each of the three must be small enough to be either (it reserves what
     * they declare). Anything else is not OFF. */
    int header = off_header(tok), headerless = 0;
    if (header == 2)
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: OFF variant '%s' (4D or n-D) is not supported", path, tok);
    if (!header) {
        if (parse_count(tok) < 0)
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: not an OFF file: it starts with '%s'", path, tok);
        r->pos -= strlen(tok) < r->pos ? strlen(tok) : r->pos; /* this line holds the counts */
        headerless = 1;
    }
    long long counts[3] = {-1, -1, 0};
    int have = 0;
    /* assimp reads the counts as numbers wherever the lines break. */
    for (int pass = 0; have < 2; pass++) {
        if (pass > 0) {
            skip_line(r);
            if (!off_next_line(r, &line))
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: OFF header ends before its counts", path);
        }
        while (have < 3 && next_token(r, tok, sizeof tok, 1)) {
            if (tok[0] == '#') break;
            counts[have] = parse_count(tok);
            if (counts[have] < 0)
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: line %lld: OFF count '%s' is not a count",
                                  path, line, tok);
            have++;
        }
    }
    if (headerless && (counts[0] > size / 4 || counts[1] > size / 4 || counts[2] > size / 4))
        return pelt__fail(err, PELT_ERR_FORMAT,
                          "%s: OFF file without a header declares counts %lld %lld %lld but has only %lld "
                          "bytes",
                          path, counts[0], counts[1], counts[2], size);
    const long long nv = counts[0], nf = counts[1];
    if (nv > size / 6 || nf > size / 4 || nv * 6 + nf * 4 > size)
        return pelt__fail(err, PELT_ERR_FORMAT,
                          "%s: OFF header declares %lld vertices and %lld faces but the file has only "
                          "%lld bytes",
                          path, nv, nf, size);
    skip_line(r);
    for (long long v = 0; v < nv; v++) {
        int coords = 0;
        if (off_next_line(r, &line)) {
            while (coords < 3 && next_token(r, tok, sizeof tok, 1) && is_decimal(tok)) coords++;
        }
        if (coords < 3)
            return pelt__fail(err, PELT_ERR_FORMAT,
                              "%s: line %lld: vertex %lld of %lld does not have 3 coordinates", path,
                              line, v, nv);
        skip_line(r);
    }
    for (long long f = 0; f < nf; f++) {
        if (!off_next_line(r, &line) || !next_token(r, tok, sizeof tok, 1))
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: file ends at face %lld of %lld", path, f, nf);
        long long n = parse_count(tok);
        if (n < 0 || n > nv)
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: line %lld: face %lld has '%s' corners", path,
                              line, f, tok);
        for (long long k = 0; k < n; k++) {
            long long i = next_token(r, tok, sizeof tok, 1) ? parse_count(tok) : -2;
            if (i == -2)
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: line %lld: face %lld has %lld of %lld corners",
                                  path, line, f, k, n);
            if (i < 0 || i >= nv)
                return pelt__fail(err, PELT_ERR_FORMAT,
                                  "%s: line %lld: face %lld refers to vertex '%s' but there are %lld "
                                  "vertices",
                                  path, line, f, tok, nv);
        }
        skip_line(r);
    }
    return PELT_OK;
}

/* Bytes of a PLY scalar type; 0 for a name PLY does not have. */
static int ply_type_size(const char *t)
{
    static const struct { const char *name; int bytes; } types[] = {
        {"char", 1},  {"uchar", 1},  {"int8", 1},   {"uint8", 1},   {"short", 2},  {"ushort", 2},
        {"int16", 2}, {"uint16", 2}, {"int", 4},    {"uint", 4},    {"int32", 4},  {"uint32", 4},
        {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
        if (!strcmp(t, types[i].name)) return types[i].bytes;
    return 0;
}

static long long line_at(const text_reader *r, size_t pos);

/* Text formats hold no control character but tabs and line breaks (LF or
 * CR LF): assimp ends a line at a lone CR or a form feed where pelt's
 * reader does not, and stops at a NUL, and leaked on each. The first bad
 * byte of [from, to) fails with what and where. */
static pelt_status check_text(const char *path, const char *what, const text_reader *r, size_t from,
                              size_t to, pelt_error *err)
{
    for (size_t i = from; i < to; i++) {
        unsigned char c = (unsigned char)r->s[i];
        if (c >= 0x20 || c == '\t' || c == '\n' || (c == '\r' && i + 1 < r->len && r->s[i + 1] == '\n'))
            continue;
        if (c == 0)
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: line %lld: %s holds a NUL byte (it must be text)",
                              path, line_at(r, i), what);
        return pelt__fail(err, PELT_ERR_FORMAT,
                          "%s: line %lld: %s holds control character 0x%02x (text has only tabs and line "
                          "breaks)",
                          path, line_at(r, i), what, c);
    }
    return PELT_OK;
}

/* A PLY header as far as the body check needs it. */
#define PLY_MAX_ELEMENTS 16
#define PLY_MAX_PROPERTIES 64
typedef struct ply_property {
    char name[64];
    int count_bytes; /* 0 for a scalar, else the bytes of a list's count */
    int bytes;       /* of the scalar or of each list entry */
    int count_signed;
    int integer;     /* the scalar or the list entries are of an integer type */
} ply_property;
typedef struct ply_element {
    char name[64];
    long long count;
    int property_count;
    ply_property properties[PLY_MAX_PROPERTIES];
} ply_element;
typedef struct ply_header {
    int format; /* 0 ascii, 1 binary little endian, 2 binary big endian */
    int element_count;
    ply_element elements[PLY_MAX_ELEMENTS];
} ply_header;

static pelt_status parse_ply_header(const char *path, text_reader *r, long long size, ply_header *h,
                                    pelt_error *err)
{
    char tok[128];
    h->format = -1;
    skip_line(r); /* "ply" */
    for (;;) {
        if (!next_token(r, tok, sizeof tok, 0))
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY header has no end_header", path);
        int is_comment = !strcmp(tok, "comment") || !strcmp(tok, "obj_info");
        if (!strcmp(tok, "end_header")) {
            if (next_token(r, tok, sizeof tok, 1))
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: line %lld: '%s' after end_header", path,
                                  line_at(r, r->pos), tok);
            break;
        }
        if (!strcmp(tok, "format")) {
            if (h->format >= 0)
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: line %lld: a second PLY format line", path,
                                  line_at(r, r->pos));
            next_token(r, tok, sizeof tok, 1);
            h->format = !strcmp(tok, "ascii")                  ? 0
                        : !strcmp(tok, "binary_little_endian") ? 1
                        : !strcmp(tok, "binary_big_endian")    ? 2
                                                               : -1;
            if (h->format < 0)
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY format '%s' is not a PLY format", path, tok);
            if (!next_token(r, tok, sizeof tok, 1) || strcmp(tok, "1.0"))
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY format version is not 1.0", path);
        } else if (!strcmp(tok, "element")) {
            if (h->element_count == PLY_MAX_ELEMENTS)
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY header has more than %d elements", path,
                                  PLY_MAX_ELEMENTS);
            ply_element *e = &h->elements[h->element_count++];
            if (!next_token(r, e->name, sizeof e->name, 1) || !next_token(r, tok, sizeof tok, 1))
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY element line is incomplete", path);
            for (int k = 0; k + 1 < h->element_count; k++)
                if (!strcmp(h->elements[k].name, e->name))
                    return pelt__fail(err, PELT_ERR_FORMAT, "%s: line %lld: a second PLY element '%s'",
                                      path, line_at(r, r->pos), e->name);
            e->count = parse_count(tok);
            if (e->count < 0)
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY element '%s' has count '%s', not a count",
                                  path, e->name, tok);
            if (e->count > size)
                return pelt__fail(err, PELT_ERR_FORMAT,
                                  "%s: PLY header declares %lld '%s' elements but the file has only %lld "
                                  "bytes",
                                  path, e->count, e->name, size);
        } else if (strcmp(tok, "property") != 0) {
            if (strcmp(tok, "comment") && strcmp(tok, "obj_info"))
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: line %lld: PLY header line starts with '%s'",
                                  path, line_at(r, r->pos), tok);
        } else {
            if (h->element_count == 0)
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY property before any element", path);
            ply_element *e = &h->elements[h->element_count - 1];
            if (e->property_count == PLY_MAX_PROPERTIES)
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY element '%s' has more than %d properties",
                                  path, e->name, PLY_MAX_PROPERTIES);
            ply_property *p = &e->properties[e->property_count++];
            if (!next_token(r, tok, sizeof tok, 1))
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY property line is incomplete", path);
            if (!strcmp(tok, "list")) {
                if (!next_token(r, tok, sizeof tok, 1))
                    return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY list property is incomplete", path);
                p->count_bytes = ply_type_size(tok);
                p->count_signed = tok[0] != 'u';
                if (p->count_bytes == 0 || p->count_bytes == 8 || !strncmp(tok, "float", 5))
                    return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY list count type '%s' is not an integer",
                                      path, tok);
                if (!next_token(r, tok, sizeof tok, 1))
                    return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY list property is incomplete", path);
            }
            p->bytes = ply_type_size(tok);
            p->integer = strncmp(tok, "float", 5) && strcmp(tok, "double");
            if (p->bytes == 0)
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY property type '%s' is not a PLY type",
                                  path, tok);
            if (!next_token(r, p->name, sizeof p->name, 1))
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY property has no name", path);
        }
        /* Nothing more on a line than its keyword needs (assimp reads more). */
        if (!is_comment && next_token(r, tok, sizeof tok, 1))
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: line %lld: PLY header line has '%s' too many",
                              path, line_at(r, r->pos), tok);
        skip_line(r);
    }
    skip_line(r);
    if (h->format < 0) return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY header has no format line", path);
    int xyz = 0;
    for (int ei = 0; ei < h->element_count; ei++) {
        const ply_element *e = &h->elements[ei];
        if (strcmp(e->name, "vertex")) continue;
        for (int pi = 0; pi < e->property_count; pi++)
            if (!e->properties[pi].count_bytes && strlen(e->properties[pi].name) == 1 &&
                strchr("xyz", e->properties[pi].name[0]))
                xyz |= 1 << (e->properties[pi].name[0] - 'x');
    }
    if (xyz != 7)
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY has no 'vertex' element with x, y and z", path);
    return PELT_OK;
}

/* The corner list of a face: fewer than 3 entries is not a face. */
static int ply_is_corner_list(const ply_element *e, const ply_property *p)
{
    return p->count_bytes && !strcmp(e->name, "face") &&
           (!strcmp(p->name, "vertex_indices") || !strcmp(p->name, "vertex_index"));
}

/* A binary list count of n bytes at p; -1 when negative. */
static long long ply_binary_count(const unsigned char *p, int n, int big_endian, int is_signed)
{
    unsigned long long v = 0;
    for (int k = 0; k < n; k++) v |= (unsigned long long)p[big_endian ? k : n - 1 - k] << (8 * (n - 1 - k));
    if (is_signed && (v >> (8 * n - 1)) & 1) return -1;
    return (long long)v;
}

/* The binary body: every element's scalars and every list's declared
 * entries are there. */
static pelt_status check_ply_binary(const char *path, const text_reader *r, const ply_header *h,
                                    pelt_error *err)
{
    const unsigned char *s = (const unsigned char *)r->s;
    size_t at = r->pos;
    for (int ei = 0; ei < h->element_count; ei++) {
        const ply_element *e = &h->elements[ei];
        for (long long i = 0; i < e->count; i++) {
            for (int pi = 0; pi < e->property_count; pi++) {
                const ply_property *p = &e->properties[pi];
                long long n = 1;
                if (p->count_bytes) {
                    if (r->len - at < (size_t)p->count_bytes)
                        return pelt__fail(err, PELT_ERR_FORMAT,
                                          "%s: PLY file ends in '%s' %lld of %lld (property '%s')", path,
                                          e->name, i, e->count, p->name);
                    n = ply_binary_count(s + at, p->count_bytes, h->format == 2, p->count_signed);
                    at += (size_t)p->count_bytes;
                    if (n < 0)
                        return pelt__fail(err, PELT_ERR_FORMAT,
                                          "%s: PLY list '%s' of '%s' %lld has a negative count", path,
                                          p->name, e->name, i);
                    if (n < 3 && ply_is_corner_list(e, p))
                        return pelt__fail(err, PELT_ERR_FORMAT,
                                          "%s: PLY face %lld has %lld corners; a face needs 3 or more",
                                          path, i, n);
                }
                if ((unsigned long long)n * (unsigned)p->bytes > r->len - at) {
                    if (!p->count_bytes)
                        return pelt__fail(err, PELT_ERR_FORMAT,
                                          "%s: PLY file ends in '%s' %lld of %lld (property '%s')", path,
                                          e->name, i, e->count, p->name);
                    return pelt__fail(err, PELT_ERR_FORMAT,
                                      "%s: PLY list '%s' of '%s' %lld of %lld declares %lld entries but "
                                      "the file ends first",
                                      path, p->name, e->name, i, e->count, n);
                }
                at += (size_t)n * (unsigned)p->bytes;
            }
        }
    }
    return PELT_OK;
}

/* The ASCII body: one line per element, holding exactly its scalars and
 * the entries its lists declare. */
static pelt_status check_ply_ascii(const char *path, text_reader *r, const ply_header *h,
                                   pelt_error *err)
{
    char tok[128];
    long long line = 0; /* the header's lines first */
    for (size_t i = 0; i < r->pos; i++) line += r->s[i] == '\n';
    for (int ei = 0; ei < h->element_count; ei++) {
        const ply_element *e = &h->elements[ei];
        for (long long i = 0; i < e->count; i++) {
            if (!next_content_line(r, &line, 0)) /* '#' starts no comment in a PLY body */
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: PLY file ends at '%s' %lld of %lld", path,
                                  e->name, i, e->count);
            for (int pi = 0; pi < e->property_count; pi++) {
                const ply_property *p = &e->properties[pi];
                long long n = 1;
                if (p->count_bytes) {
                    if (!next_token(r, tok, sizeof tok, 1) || (n = parse_count(tok)) < 0)
                        return pelt__fail(err, PELT_ERR_FORMAT,
                                          "%s: line %lld: PLY '%s' %lld: list '%s' has no count", path,
                                          line, e->name, i, p->name);
                    if (n < 3 && ply_is_corner_list(e, p))
                        return pelt__fail(err, PELT_ERR_FORMAT,
                                          "%s: line %lld: PLY face %lld has %lld corners; a face needs 3 "
                                          "or more",
                                          path, line, i, n);
                }
                for (long long k = 0; k < n; k++) {
                    if (next_token(r, tok, sizeof tok, 1)) {
                        /* assimp reads "213.8" for a uchar as 213 and ".8" as the next value */
                        if (p->integer ? is_integer(tok) : is_decimal(tok)) continue;
                        return pelt__fail(err, PELT_ERR_FORMAT,
                                          "%s: line %lld: PLY '%s' %lld: '%s' (property '%s') is not %s",
                                          path, line, e->name, i, tok, p->name,
                                          p->integer ? "an integer" : "a number");
                    }
                    if (!p->count_bytes)
                        return pelt__fail(err, PELT_ERR_FORMAT,
                                          "%s: line %lld: PLY '%s' %lld ends before property '%s'", path,
                                          line, e->name, i, p->name);
                    return pelt__fail(err, PELT_ERR_FORMAT,
                                      "%s: line %lld: PLY '%s' %lld: list '%s' declares %lld entries but "
                                      "the line holds %lld",
                                      path, line, e->name, i, p->name, n, k);
                }
            }
            if (next_token(r, tok, sizeof tok, 1))
                return pelt__fail(err, PELT_ERR_FORMAT,
                                  "%s: line %lld: PLY '%s' %lld holds more values than its properties "
                                  "declare ('%s')",
                                  path, line, e->name, i, tok);
            skip_line(r);
        }
    }
    return PELT_OK;
}

/* PLY: the body must hold exactly what the header declares, lists
 * included: a list that declares more entries than there are would make
 * assimp read the next element's values as indices (a silently wrong
 * mesh), and a truncated ASCII body makes it leak. */
static pelt_status check_ply(const char *path, text_reader *r, long long size, pelt_error *err)
{
    if (r->len < 4 || (strncmp(r->s, "ply", 3) && strncmp(r->s, "PLY", 3)) ||
        !isspace((unsigned char)r->s[3]))
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: not a PLY file: it does not start with 'ply'", path);
    ply_header *h = pelt__calloc(1, sizeof *h);
    if (!h) return pelt__fail(err, PELT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    pelt_status st = parse_ply_header(path, r, size, h, err);
    if (st == PELT_OK) st = check_text(path, "the PLY header", r, 0, r->pos, err);
    if (st == PELT_OK && h->format == 0) st = check_text(path, "ASCII PLY", r, r->pos, r->len, err);
    if (st == PELT_OK)
        st = h->format == 0 ? check_ply_ascii(path, r, h, err) : check_ply_binary(path, r, h, err);
    free(h);
    return st;
}

/* OBJ: every face has three or more corners and each corner names a
 * vertex of the file (1-based, or negative: counted back from the last
 * vertex so far). assimp makes a face of one or two corners a point or a
 * line and pelt would drop it: a silently partial mesh. */
static pelt_status check_obj(const char *path, text_reader *r, pelt_error *err)
{
    char tok[128];
    long long vertices = 0, line = 1;
    text_reader count = *r;
    while (count.pos < count.len) { /* forward references are allowed: count them all first */
        if (next_token(&count, tok, sizeof tok, 1) && !strcmp(tok, "v")) vertices++;
        skip_line(&count);
    }
    long long seen = 0;
    for (; r->pos < r->len; line++) {
        if (!next_token(r, tok, sizeof tok, 1) || (strcmp(tok, "f") && strcmp(tok, "v"))) {
            skip_line(r);
            continue;
        }
        if (!strcmp(tok, "v")) {
            seen++;
            skip_line(r);
            continue;
        }
        long long corners = 0;
        for (;;) {
            if (!next_token(r, tok, sizeof tok, 1)) break;
            if (!strcmp(tok, "\\")) { /* the face goes on on the next line */
                skip_line(r);
                line++;
                continue;
            }
            char *end;
            errno = 0;
            long long i = strtoll(tok, &end, 10);
            if (end == tok || (*end != '\0' && *end != '/'))
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: line %lld: face corner '%s' is not a vertex index",
                                  path, line, tok);
            if (errno == ERANGE || i == 0 || i > vertices || (i < 0 && -i > seen))
                return pelt__fail(err, PELT_ERR_FORMAT,
                                  "%s: line %lld: face refers to vertex '%s' but there are %lld vertices%s",
                                  path, line, tok, i < 0 ? seen : vertices, i < 0 ? " before it" : "");
            corners++;
        }
        if (corners < 3)
            return pelt__fail(err, PELT_ERR_FORMAT,
                              "%s: line %lld: a face of %lld corner%s; a face needs 3 or more ('l' makes "
                              "a line)",
                              path, line, corners, corners == 1 ? "" : "s");
        skip_line(r);
    }
    return PELT_OK;
}

/* The 1-based line of position pos. */
static long long line_at(const text_reader *r, size_t pos)
{
    long long line = 1;
    for (size_t i = 0; i < pos && i < r->len; i++) line += r->s[i] == '\n';
    return line;
}

/* Keywords are lower case: assimp reads "vErtex" as something else and leaks. */
static int word_is(const char *tok, const char *word)
{
    return strcmp(tok, word) == 0;
}

/* Reads n numbers; false (with k the one missing) when one is not. */
static int stl_numbers(text_reader *r, int n, int *k)
{
    char tok[64];
    for (*k = 0; *k < n; (*k)++)
        if (!next_token(r, tok, sizeof tok, 1) || !is_decimal(tok)) return 0;
    return 1;
}

/* ASCII STL, word by word: solid NAME { facet normal N N N outer loop
 * (vertex X Y Z){3} endloop endfacet } endsolid, and maybe another solid.
 * assimp leaks memory on a truncated file and on a misspelt keyword. */
static pelt_status check_stl_ascii(const char *path, const text_reader *head, pelt_error *err)
{
    pelt_status st = check_text(path, "ASCII STL", head, 0, head->len, err);
    if (st) return st;
    static const char *const facet[] = {"outer", "loop", "vertex", "vertex", "vertex", "endloop", "endfacet"};
    text_reader r = *head;
    char tok[64];
    long long vertices = 0, facets = 0;
    skip_line(&r); /* solid NAME */
    for (;;) {
        if (!next_token(&r, tok, sizeof tok, 0))
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: ASCII STL is truncated (%lld vertices, no endsolid)",
                              path, vertices);
        if (word_is(tok, "endsolid")) {
            skip_line(&r);
            if (!next_token(&r, tok, sizeof tok, 0)) return PELT_OK;
            if (word_is(tok, "solid")) {
                skip_line(&r);
                continue;
            }
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: line %lld: '%s' after endsolid", path,
                              line_at(&r, r.pos), tok);
        }
        int k;
        if (!word_is(tok, "facet") || !next_token(&r, tok, sizeof tok, 1) || !word_is(tok, "normal"))
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: line %lld: STL facet %lld does not start with "
                              "'facet normal'", path, line_at(&r, r.pos), facets);
        if (!stl_numbers(&r, 3, &k))
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: line %lld: STL facet %lld: normal lacks coordinate %d",
                              path, line_at(&r, r.pos), facets, k);
        for (size_t w = 0; w < sizeof facet / sizeof facet[0]; w++) {
            if (!next_token(&r, tok, sizeof tok, 0))
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: ASCII STL is truncated (%lld vertices, no endsolid)",
                                  path, vertices);
            if (!word_is(tok, facet[w]))
                return pelt__fail(err, PELT_ERR_FORMAT, "%s: line %lld: STL facet %lld: '%s' where '%s' belongs",
                                  path, line_at(&r, r.pos), facets, tok, facet[w]);
            if (!strcmp(facet[w], "vertex")) {
                if (!stl_numbers(&r, 3, &k))
                    return pelt__fail(err, PELT_ERR_FORMAT, "%s: STL vertex %lld lacks coordinate %d", path,
                                      vertices, k);
                vertices++;
            }
        }
        facets++;
    }
}

/* STL as assimp tells them apart: binary when the size is exactly the 84
 * header bytes and 50 per triangle of its count; else ASCII when it starts
 * with "solid" after white space (some binary writers start the header with
 * it too: one that is not text is reported as a cut binary file). */
static pelt_status check_stl(const char *path, const text_reader *r, long long size, pelt_error *err)
{
    long long n = -1;
    if (r->len >= 84) {
        const unsigned char *u = (const unsigned char *)r->s + 80;
        n = (long long)u[0] | (long long)u[1] << 8 | (long long)u[2] << 16 | (long long)u[3] << 24;
    }
    if (n >= 0 && 84 + 50 * n == size) return PELT_OK;
    size_t at = 0;
    while (at < r->len && isspace((unsigned char)r->s[at])) at++;
    int solid = r->len - at >= 5 && !strncmp(r->s + at, "solid", 5);
    pelt_error text_err = {0};
    if (solid && (n < 0 || check_text(path, "ASCII STL", r, 0, r->len, &text_err) == PELT_OK))
        return check_stl_ascii(path, r, err);
    if (n < 0)
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: binary STL shorter than its 84-byte header", path);
    return pelt__fail(err, PELT_ERR_FORMAT,
                      "%s: binary STL declares %lld triangles (%lld bytes) but the file has %lld bytes", path,
                      n, 84 + 50 * n, size);
}

static uint32_t u32_le(const char *p)
{
    const unsigned char *u = (const unsigned char *)p;
    return (uint32_t)u[0] | (uint32_t)u[1] << 8 | (uint32_t)u[2] << 16 | (uint32_t)u[3] << 24;
}

/* glTF JSON starts with '{' (after white space or a byte order mark). assimp
 * guesses a format for anything else and one of its guesses reads past the
 * end of the buffer. */
static int is_json_object(const char *s, size_t len)
{
    size_t i = len >= 3 && !memcmp(s, "\xef\xbb\xbf", 3) ? 3 : 0;
    while (i < len && isspace((unsigned char)s[i])) i++;
    return i < len && s[i] == '{';
}

/* GLB: the lengths in the header and the chunk headers fit in the file
 * (assimp allocates a chunk's declared length before reading it). */
static pelt_status check_glb(const char *path, const text_reader *r, long long size, pelt_error *err)
{
    if (r->len < 4 || memcmp(r->s, "glTF", 4))
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: not a GLB file: it does not start with 'glTF'", path);
    if (r->len < 12) return pelt__fail(err, PELT_ERR_FORMAT, "%s: GLB header is truncated", path);
    uint32_t version = u32_le(r->s + 4), total = u32_le(r->s + 8);
    if ((long long)total > size)
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: GLB header declares %u bytes but the file has %lld",
                          path, total, size);
    if (version == 1) { /* glTF 1.0: one content block after a 20-byte header */
        if (r->len < 20 || (long long)u32_le(r->s + 12) > size - 20)
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: GLB content is longer than the file", path);
        return PELT_OK;
    }
    size_t at = 12;
    for (int chunk = 0; at + 8 <= total && at + 8 <= r->len; chunk++) {
        uint32_t n = u32_le(r->s + at);
        if (n > total - at - 8)
            return pelt__fail(err, PELT_ERR_FORMAT,
                              "%s: GLB chunk %d declares %u bytes but only %zu follow", path, chunk, n,
                              (size_t)total - at - 8);
        if (chunk == 0 && (memcmp(r->s + at + 4, "JSON", 4) || !is_json_object(r->s + at + 8, n)))
            return pelt__fail(err, PELT_ERR_FORMAT, "%s: GLB does not start with a JSON chunk", path);
        at += 8 + (size_t)n;
    }
    return PELT_OK;
}

static pelt_status check_gltf(const char *path, const text_reader *r, pelt_error *err)
{
    if (!is_json_object(r->s, r->len))
        return pelt__fail(err, PELT_ERR_FORMAT, "%s: not a glTF file: it does not start with a JSON object",
                          path);
    return PELT_OK;
}

typedef enum file_kind { KIND_OTHER, KIND_OFF, KIND_PLY, KIND_STL, KIND_OBJ, KIND_GLB, KIND_GLTF } file_kind;

/* By content first (assimp also sniffs), then by extension. */
static file_kind sniff(const char *path, const char *head, size_t len)
{
    if (len >= 3 && (strncmp(head, "ply", 3) == 0 || strncmp(head, "PLY", 3) == 0)) return KIND_PLY;
    if (len >= 4 && memcmp(head, "glTF", 4) == 0) return KIND_GLB;
    text_reader probe = {head, 0, len};
    char tok[16];
    long long line = 0;
    if (off_next_line(&probe, &line) && next_token(&probe, tok, sizeof tok, 1) && strlen(tok) <= 6 &&
        ends_with_ci(tok, "OFF"))
        return KIND_OFF;
    if (ends_with_ci(path, ".off")) return KIND_OFF;
    if (ends_with_ci(path, ".stl")) return KIND_STL;
    if (ends_with_ci(path, ".obj")) return KIND_OBJ;
    if (ends_with_ci(path, ".ply")) return KIND_PLY;
    if (ends_with_ci(path, ".gltf")) return KIND_GLTF;
    if (ends_with_ci(path, ".glb")) return KIND_GLB;
    return KIND_OTHER;
}

/* Checks what the header of a file (or buffer) named `name` declares.
 * buf holds its first len bytes of size in all; for OFF, PLY, STL and OBJ it
 * holds all of them. */
pelt_status pelt__mesh_check(const char *name, const char *buf, size_t len, long long size,
                             pelt_error *err)
{
    if (len == 0) return pelt__fail(err, PELT_ERR_FORMAT, "%s: file is empty", name);
    file_kind kind = sniff(name, buf, len);
    text_reader r = {buf, 0, len};
    if (kind == KIND_OFF || kind == KIND_OBJ) {
        pelt_status st = check_text(name, kind == KIND_OFF ? "an OFF file" : "an OBJ file", &r, 0, len, err);
        if (st) return st;
    }
    if (kind == KIND_OFF) return check_off(name, &r, size, err);
    if (kind == KIND_PLY) return check_ply(name, &r, size, err);
    if (kind == KIND_STL) return check_stl(name, &r, size, err);
    if (kind == KIND_OBJ) return check_obj(name, &r, err);
    if (kind == KIND_GLB) return check_glb(name, &r, size, err);
    if (kind == KIND_GLTF) return check_gltf(name, &r, err);
    return PELT_OK;
}

bool pelt__mesh_check_reads_whole(const char *name, const char *head, size_t len)
{
    return sniff(name, head, len) != KIND_OTHER;
}
