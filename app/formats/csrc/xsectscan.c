/* app.formats._xsectscan: the design cross sections of a LandXML <CrossSects> read in C (app/formats/landxml.py).
 *
 * The compiled twin of the Python scan there (landxml._scan_region_python is the reference and the fallback where
 * no C compiler built this module; tests/road/test_landxml_scan.py checks the two, and the tree's reading, agree).
 * Why it exists: a design file's cross sections (one every 50 m, three points each) make the document four times
 * larger, and the Python scan spent about a second on them at 200,000 curves (regular expressions, a bytes object
 * per number, each number converted by a Python call), where issue 39 allows a third of the reading's time.
 *
 * scan(chunk) -> (stations, counts, values, picks) | None. `chunk` (a bytes-like object) is part of a
 * <CrossSects>'s content, whole sections; the answer is four bytes objects (native doubles, int64, doubles,
 * doubles): each section's `sta`, how many numbers its points have (two a point), the points' numbers in order, and
 * per section the five numbers landxml._slopes_from takes (the offset and elevation of the point nearest the
 * centreline on the left, the same on the right, and the elevation of the last point at offset 0; nan where there is
 * none), picked as landxml._slopes picks them (the arithmetic stays numpy's, the same for every path). None:
 * the chunk holds something this scan does not take, and the caller reads the whole content with the Python scan
 * (which takes more shapes and refuses bad numbers word for word as the tree's reading does). Taken is only this,
 * with XML's white space (space, tab, line feed, carriage return) where shown as S:
 *
 *   S? ( <CrossSect ATTRS> S? <DesignCrossSectSurf ATTRS>
 *        ( S? <CrossSectPnt S? > S? NUM S NUM S? </CrossSectPnt S? > )*
 *        S? </DesignCrossSectSurf S? > S? </CrossSect S? > S? )*
 *
 * ATTRS: ( S NAME S? = S? ("value" | 'value') )* S? with NAME as the Python scan's (ASCII letters, digits, "._-", not
 * starting with a digit, '.', '-' or "xml" in any case), the names of one tag distinct, a value holding none of
 * < > & and no control character but white space; a <CrossSect> has a `sta` whose value, less white space at its
 * ends, is a NUM. NUM: [+-]? (digits [. digits?] | . digits) ([eE] [+-]? digits)?, and finite. Everything the
 * scan takes is thus well-formed by itself (the Python scan's proof: no reference, no "]]>", distinct plain
 * attribute names, only the three tags, nested), and every number is one the tree's reading converts the same.
 *
 * Numbers are converted exactly as Python's float() converts them (both correctly rounded): a NUM of at most 19
 * significant digits whose value m * 10^e has m <= 2^53 and |e| <= 22 in one IEEE operation (m and 10^|e| are exact
 * doubles: the product or quotient is the correctly rounded value, Clinger's fast path), any other by
 * PyOS_string_to_double (Python's own conversion). The GIL is held: the caller hands in chunks of about a MiB and
 * lets other threads run between them (the Python scan's chunks). No recursion; every read is checked against the
 * chunk's end.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

/* attributes a tag may have here (more: the Python scan reads it) */
#define MAX_ATTRS 16

typedef struct {
    char *data;
    Py_ssize_t n, cap; /* bytes used and allocated */
} vec_t;

typedef struct {
    const char *p, *end;
    vec_t stations, counts, values, picks;
} scan_t;

enum { OK = 0, DECLINE = 1, FAIL = -1 }; /* FAIL: a Python exception is set */

static int push(vec_t *v, const void *item, Py_ssize_t size) {
    if (v->cap - v->n < size) {
        Py_ssize_t cap = v->cap ? v->cap : 4096;
        while (cap - v->n < size) {
            if (cap > PY_SSIZE_T_MAX / 2)
                return FAIL;
            cap *= 2;
        }
        char *d = PyMem_Realloc(v->data, (size_t)cap);
        if (d == NULL) {
            PyErr_NoMemory();
            return FAIL;
        }
        v->data = d;
        v->cap = cap;
    }
    memcpy(v->data + v->n, item, (size_t)size);
    v->n += size;
    return OK;
}

static inline int is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
static inline int is_digit(char c) { return c >= '0' && c <= '9'; }
static inline int is_name_start(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; }
static inline int is_name_char(char c) { return is_name_start(c) || is_digit(c) || c == '.' || c == '-'; }

static inline void skip_space(scan_t *s) {
    while (s->p < s->end && is_space(*s->p))
        s->p++;
}

/* the literal `lit` (of `len` bytes) at the current place: taken */
static inline int take(scan_t *s, const char *lit, Py_ssize_t len) {
    if (s->end - s->p < len || memcmp(s->p, lit, (size_t)len) != 0)
        return 0;
    s->p += len;
    return 1;
}
#define TAKE(s, lit) take((s), (lit), (Py_ssize_t)(sizeof(lit) - 1))

static const double POW10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/* the NUM in [p, e) (all of it) as float() reads it: OK, DECLINE (not a NUM, or not finite) or FAIL */
static int number(const char *p, const char *e, double *out) {
    const char *start = p;
    int negative = 0, digits = 0, hard = 0, kept = 0;
    uint64_t m = 0;
    long e10 = 0;
    if (p < e && (*p == '+' || *p == '-'))
        negative = *p++ == '-';
    for (; p < e && is_digit(*p); p++) {
        digits = 1;
        if (m == 0 && *p == '0')
            continue; /* a leading zero */
        if (kept < 19) {
            m = m * 10 + (uint64_t)(*p - '0');
            kept++;
        } else
            hard = 1;
    }
    if (p < e && *p == '.') {
        for (p++; p < e && is_digit(*p); p++) {
            digits = 1;
            if (m == 0 && *p == '0') {
                e10--;
                continue;
            }
            if (kept < 19) {
                m = m * 10 + (uint64_t)(*p - '0');
                kept++;
                e10--;
            } else
                hard = 1;
        }
    }
    if (!digits)
        return DECLINE;
    if (p < e && (*p == 'e' || *p == 'E')) {
        int minus = 0;
        long x = 0;
        p++;
        if (p < e && (*p == '+' || *p == '-'))
            minus = *p++ == '-';
        if (!(p < e && is_digit(*p)))
            return DECLINE;
        for (; p < e && is_digit(*p); p++)
            if (x < 100000)
                x = x * 10 + (*p - '0');
            else
                hard = 1; /* an exponent this long: Python's conversion says what it is */
        e10 += minus ? -x : x;
    }
    if (p != e)
        return DECLINE;
    if (m == 0 && !hard) {
        *out = negative ? -0.0 : 0.0;
        return OK;
    }
#if FLT_EVAL_METHOD == 0 /* double arithmetic in doubles (SSE2, AArch64): the fast path is exact there */
    if (!hard && m <= ((uint64_t)1 << 53) && e10 >= -22 && e10 <= 22) {
        double v = (double)m;
        v = e10 < 0 ? v / POW10[-e10] : v * POW10[e10];
        *out = negative ? -v : v;
        return OK;
    }
#endif
    {
        Py_ssize_t len = e - start;
        char small[64];
        char *buf = len < (Py_ssize_t)sizeof(small) ? small : PyMem_Malloc((size_t)len + 1);
        char *stop = NULL;
        double v;
        if (buf == NULL) {
            PyErr_NoMemory();
            return FAIL;
        }
        memcpy(buf, start, (size_t)len);
        buf[len] = '\0';
        v = PyOS_string_to_double(buf, &stop, NULL); /* no exception for an overflow: +-inf, declined below */
        int whole = stop == buf + len;
        if (buf != small)
            PyMem_Free(buf);
        if (v == -1.0 && PyErr_Occurred()) {
            if (!PyErr_ExceptionMatches(PyExc_ValueError))
                return FAIL;
            PyErr_Clear();
            return DECLINE;
        }
        if (!whole || !isfinite(v))
            return DECLINE;
        *out = v;
        return OK;
    }
}

/* a start tag's attributes and its '>' (the name taken already); `sta`: where the value of `sta` goes (NULL: not
 * wanted), set to NULL where the tag has none */
static int attributes(scan_t *s, const char **sta, const char **sta_end) {
    const char *names[MAX_ATTRS], *name_ends[MAX_ATTRS];
    int n = 0;
    if (sta != NULL)
        *sta = *sta_end = NULL;
    for (;;) {
        const char *before = s->p;
        skip_space(s);
        if (s->p < s->end && *s->p == '>') {
            s->p++;
            break;
        }
        if (s->p == before || n == MAX_ATTRS) /* an attribute after no white space, "/>", or anything else */
            return DECLINE;
        if (!(s->p < s->end && is_name_start(*s->p)))
            return DECLINE;
        const char *name = s->p;
        while (s->p < s->end && is_name_char(*s->p))
            s->p++;
        if (s->p - name >= 3 && (name[0] | 0x20) == 'x' && (name[1] | 0x20) == 'm' && (name[2] | 0x20) == 'l')
            return DECLINE; /* reserved to XML (xmlns among them) */
        for (int k = 0; k < n; k++)
            if (name_ends[k] - names[k] == s->p - name && memcmp(names[k], name, (size_t)(s->p - name)) == 0)
                return DECLINE; /* a name twice: not well-formed; the Python scan and the guard say so */
        names[n] = name;
        name_ends[n] = s->p;
        n++;
        skip_space(s);
        if (!TAKE(s, "="))
            return DECLINE;
        skip_space(s);
        if (!(s->p < s->end && (*s->p == '"' || *s->p == '\'')))
            return DECLINE;
        const char quote = *s->p++;
        const char *value = s->p;
        while (s->p < s->end && *s->p != quote) {
            const unsigned char c = (unsigned char)*s->p;
            if (c == '<' || c == '>' || c == '&' || c >= 0x80 || (c < 0x20 && !is_space((char)c)))
                return DECLINE;
            s->p++;
        }
        if (s->p >= s->end)
            return DECLINE;
        if (sta != NULL && name_ends[n - 1] - name == 3 && memcmp(name, "sta", 3) == 0) {
            *sta = value;
            *sta_end = s->p;
        }
        s->p++; /* the closing quote */
    }
    return OK;
}

/* one <CrossSect> (its '<CrossSect' taken) */
static int section(scan_t *s) {
    const char *sta, *sta_end;
    double v, point[2];
    /* the points landxml._slopes picks: the nearest on the left and on the right (the first of equals: only a
     * nearer one replaces it) and the last at offset 0; nan where there is none */
    double pick[5] = {NAN, NAN, NAN, NAN, NAN}; /* x left, z left, x right, z right, z centre */
    int64_t count = 0;
    int r = attributes(s, &sta, &sta_end);
    if (r != OK)
        return r;
    if (sta == NULL)
        return DECLINE; /* no station: the Python scan refuses it as the tree's reading does */
    while (sta < sta_end && is_space(*sta))
        sta++;
    while (sta_end > sta && is_space(sta_end[-1]))
        sta_end--;
    if ((r = number(sta, sta_end, &v)) != OK)
        return r;
    if (push(&s->stations, &v, sizeof v) != OK)
        return FAIL;
    skip_space(s);
    if (!TAKE(s, "<DesignCrossSectSurf"))
        return DECLINE;
    if ((r = attributes(s, NULL, NULL)) != OK)
        return r;
    for (;;) {
        skip_space(s);
        if (!TAKE(s, "<CrossSectPnt"))
            break;
        skip_space(s);
        if (!TAKE(s, ">"))
            return DECLINE; /* attributes on a point, "/>", another name */
        for (int k = 0; k < 2; k++) {
            skip_space(s);
            const char *word = s->p;
            while (s->p < s->end && !is_space(*s->p) && *s->p != '<')
                s->p++;
            if (k == 0 && !(s->p < s->end && is_space(*s->p)))
                return DECLINE; /* one word */
            if ((r = number(word, s->p, &point[k])) != OK)
                return r;
        }
        if (push(&s->values, point, sizeof point) != OK)
            return FAIL;
        count += 2;
        if (point[0] < 0) {
            if (isnan(pick[0]) || point[0] > pick[0]) {
                pick[0] = point[0];
                pick[1] = point[1];
            }
        } else if (point[0] > 0) {
            if (isnan(pick[2]) || point[0] < pick[2]) {
                pick[2] = point[0];
                pick[3] = point[1];
            }
        } else /* 0 or -0 (every number is finite) */
            pick[4] = point[1];
        skip_space(s);
        if (!TAKE(s, "</CrossSectPnt"))
            return DECLINE; /* a third word, an element inside */
        skip_space(s);
        if (!TAKE(s, ">"))
            return DECLINE;
    }
    if (!TAKE(s, "</DesignCrossSectSurf"))
        return DECLINE;
    skip_space(s);
    if (!TAKE(s, ">"))
        return DECLINE;
    skip_space(s);
    if (!TAKE(s, "</CrossSect"))
        return DECLINE;
    skip_space(s);
    if (!TAKE(s, ">"))
        return DECLINE;
    if (push(&s->picks, pick, sizeof pick) != OK)
        return FAIL;
    return push(&s->counts, &count, sizeof count);
}

static PyObject *xsectscan_scan(PyObject *self, PyObject *args) {
    Py_buffer view;
    scan_t s;
    int r = OK;
    PyObject *out = NULL;
    (void)self;
    if (!PyArg_ParseTuple(args, "y*:scan", &view))
        return NULL;
    memset(&s, 0, sizeof s);
    s.p = view.buf;
    s.end = s.p + view.len;
    for (;;) {
        skip_space(&s);
        if (s.p == s.end)
            break;
        if (!TAKE(&s, "<CrossSect")) {
            r = DECLINE;
            break;
        }
        if ((r = section(&s)) != OK)
            break;
    }
    if (r == OK)
        out = Py_BuildValue("(y#y#y#y#)", s.stations.data ? s.stations.data : "", s.stations.n,
                            s.counts.data ? s.counts.data : "", s.counts.n, s.values.data ? s.values.data : "",
                            s.values.n, s.picks.data ? s.picks.data : "", s.picks.n);
    else if (r == DECLINE)
        out = Py_NewRef(Py_None);
    PyMem_Free(s.stations.data);
    PyMem_Free(s.counts.data);
    PyMem_Free(s.values.data);
    PyMem_Free(s.picks.data);
    PyBuffer_Release(&view);
    return out;
}

static PyMethodDef methods[] = {
    {"scan", xsectscan_scan, METH_VARARGS,
     "scan(chunk) -> (stations, counts, values, picks) as bytes of float64, int64, float64, float64, or None where the "
     "chunk holds something this scan does not take (see app/formats/csrc/xsectscan.c)."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_xsectscan", "LandXML design cross sections read in C (app.formats.landxml).", -1, methods,
};

PyMODINIT_FUNC PyInit__xsectscan(void) { return PyModule_Create(&module); }
