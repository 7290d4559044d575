/* app.formats._rowwriter: rows of text put together from segments, in C, without the GIL.
 *
 * The compiled twin of app.formats.segments.write_rows (the Python writer there is the reference and the fallback
 * where no C compiler built this module; tests/api/test_segments.py checks the two agree byte for byte). Why it
 * exists: an alignment job's result is rendered on GET, and the Python writer spends about 1.7 us a CSV row making a
 * bytes object per cell, holding the GIL that the event loop needs to send what it made (docs/jobs.md: CSV at about
 * 115 MiB/s against the 300 MiB/s of issue 22). Here a row costs the shortest-digits conversion of its numbers
 * (Ryu, vendored in ryu/: Ulf Adams, "Ryu: fast float-to-string conversion", PLDI 2018; Apache-2.0 or Boost; the
 * files of github.com/ulfjack/ryu at e3e090c66efd258a0cee50ee93411ec99668d416, unmodified) and the copies, and the
 * GIL is released while it writes.
 *
 * write(layout, n, drop) -> bytes: n rows, each the segments of `layout` in order, less the text's first `drop`
 * bytes. A segment is one of
 *   bytes                          the same text in every row;
 *   list of n bytes                row i's text is item i;
 *   (0, codes, texts)              codes: n integers (a C-contiguous buffer of Py_ssize_t, numpy's intp), texts: a
 *                                  tuple of bytes; row i's text is texts[codes[i]];
 *   (2, blob, starts, ends)        blob: bytes, starts and ends: n integers each (as codes); row i's text is
 *                                  blob[starts[i]:ends[i]] (a column of texts kept as one blob: app.formats.texts);
 *   (1, values, mode)              values: n float64 (a C-contiguous buffer of doubles), each written as Python's
 *                                  repr writes it (the shortest text that reads back to it, repr's layout: "0.0",
 *                                  "350.0", "0.0001", "1e-05", "1e+16"); mode 0 (CSV) writes nan as an empty field
 *                                  and infinities as "inf" and "-inf", mode 1 (JSON) writes nan and infinities as
 *                                  "null" (as orjson does; orjson's layout differs from repr's outside [1e-4, 1e16),
 *                                  so the caller writes such a JSON column itself: segments.repr_safe).
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>

#include "ryu/d2s.c"

/* the longest float: a sign, 17 digits, a point and "e-308" (or "0.000" and 17 digits), with room to spare */
#define FLOAT_MAX 26

enum { SEG_CONSTANT, SEG_TEXTS, SEG_CODES, SEG_SLICES, SEG_FLOATS };
enum { MODE_CSV = 0, MODE_JSON = 1 };

typedef struct {
    const char *ptr;
    Py_ssize_t len;
} text_t;

typedef struct {
    int kind;
    text_t constant;   /* SEG_CONSTANT */
    text_t *texts;     /* SEG_TEXTS: one a row; SEG_CODES: the table */
    Py_ssize_t ntexts; /* SEG_CODES */
    PyObject **held;   /* SEG_TEXTS: the rows' bytes objects, a reference each while the GIL is released */
    const Py_ssize_t *codes;
    const double *values;
    int mode;
    const char *blob; /* SEG_SLICES: row i is blob[starts[i]:ends[i]] */
    const Py_ssize_t *starts;
    const Py_ssize_t *ends;
    Py_buffer view;
    int has_view;
    Py_buffer view2;
    int has_view2;
} segment_t;

/* v's 8 decimal digits (v < 10^8, leading zeros written) at p */
static inline void put_8digits(char *p, uint32_t v) {
    const uint32_t hi = v / 10000, lo = v % 10000;
    memcpy(p, DIGIT_TABLE + 2 * (hi / 100), 2);
    memcpy(p + 2, DIGIT_TABLE + 2 * (hi % 100), 2);
    memcpy(p + 4, DIGIT_TABLE + 2 * (lo / 100), 2);
    memcpy(p + 6, DIGIT_TABLE + 2 * (lo % 100), 2);
}

/* m's decimal digits (n of them, m < 10^17) written at out: blocks of eight in 32-bit arithmetic, then pairs */
static inline void put_digits(char *out, uint64_t m, int n) {
    char *p = out + n;
    while (n > 8) {
        const uint64_t q = m / 100000000;
        p -= 8;
        put_8digits(p, (uint32_t)(m - q * 100000000));
        m = q;
        n -= 8;
    }
    uint32_t r = (uint32_t)m;
    while (r >= 100) {
        p -= 2;
        memcpy(p, DIGIT_TABLE + 2 * (r % 100), 2);
        r /= 100;
    }
    if (r >= 10) {
        p -= 2;
        memcpy(p, DIGIT_TABLE + 2 * r, 2);
    } else {
        *--p = (char)('0' + r);
    }
}

/* Whether x (positive) reads back from a decimal of at most FEW_DECIMALS decimals below 1e15 in all, and that
 * decimal (digits and exponent): the shortest, as Ryu's d2d would find it, at a few multiplications instead of its
 * digit-removal loop (an input echoed back, a radius of 350.5 m or a grade of -4.3 %, is such a number).
 * The decimal m / 10^k reads back to x exactly when the division m / 10^k, both exact (m < 2^53, 10^k <= 10^22),
 * rounds to x: IEEE division is correctly rounded, as reading a decimal is. The smallest k that succeeds gives the
 * fewest digits. The candidate is the only one of its k: with m < 1e15 neighbouring decimals m/10^k and
 * (m+1)/10^k are more than four units in the last place of x apart, so at most one reads back to x, and
 * rint(x * 10^k), off the exact x * 10^k by less than 0.2, finds it. */
#define FEW_DECIMALS 3
static inline bool few_decimals(double x, floating_decimal_64 *v) {
    static const double POW10[FEW_DECIMALS + 1] = {1e0, 1e1, 1e2, 1e3};
    if (!(x >= 1e-4 && x < 1e12)) {
        return false;
    }
    for (int k = 0; k <= FEW_DECIMALS; k++) {
        const double p = x * POW10[k];
        const double y = rint(p);
        /* the candidate lies within a few units in the last place of p (at most 0.2): the division only for
         * those (nearly every number of many digits is left by the multiplications alone) */
        if (fabs(p - y) <= p * 1e-15 && y >= 1.0 && (double)(uint64_t)y / POW10[k] == x) {
            v->mantissa = (uint64_t)y;
            v->exponent = -k;
            return true;
        }
    }
    return false;
}

/* x as repr writes it (PyOS_double_to_string(x, 'r', 0, Py_DTSF_ADD_DOT_0): the shortest digits that read back to
 * x, positional for a decimal point position in (-4, 16], else d.ddde+XX with at least two exponent digits);
 * nan and infinities by mode. Returns the end of what it wrote. */
static inline char *put_float(char *out, double x, int mode) {
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    const bool sign = (bits >> 63) != 0;
    const uint64_t mantissa = bits & ((1ull << DOUBLE_MANTISSA_BITS) - 1);
    const uint32_t exponent = (uint32_t)((bits >> DOUBLE_MANTISSA_BITS) & ((1u << DOUBLE_EXPONENT_BITS) - 1));
    if (exponent == (1u << DOUBLE_EXPONENT_BITS) - 1) {
        if (mode == MODE_JSON) {
            memcpy(out, "null", 4);
            return out + 4;
        }
        if (mantissa != 0) {
            return out; /* nan: an empty CSV field */
        }
        if (sign) {
            *out++ = '-';
        }
        memcpy(out, "inf", 3);
        return out + 3;
    }
    if (sign) {
        *out++ = '-';
    }
    if (exponent == 0 && mantissa == 0) {
        memcpy(out, "0.0", 3);
        return out + 3;
    }
    floating_decimal_64 v;
    if (!d2d_small_int(mantissa, exponent, &v) && !few_decimals(sign ? -x : x, &v)) {
        v = d2d(mantissa, exponent);
    }
    uint64_t m = v.mantissa;
    int32_t e = v.exponent;
    while (m % 10 == 0) { /* repr's digits have no trailing zero (an integer's come with them) */
        m /= 10;
        ++e;
    }
    const int n = (int)decimalLength17(m);
    const int point = e + n; /* x = 0.d1d2...dn * 10^point */
    /* the digits are written straight into out, then moved or followed as the layout asks: out has room for
     * FLOAT_MAX bytes here whatever this number's length (the caller's bound) */
    if (point <= -4 || point > 16) { /* d.ddde+XX */
        put_digits(out + 1, m, n);
        out[0] = out[1];
        if (n > 1) {
            out[1] = '.';
            out += n + 1;
        } else {
            out += 1;
        }
        int k = point - 1;
        *out++ = 'e';
        *out++ = k < 0 ? '-' : '+';
        if (k < 0) {
            k = -k;
        }
        if (k >= 100) {
            *out++ = (char)('0' + k / 100);
            k %= 100;
        }
        memcpy(out, DIGIT_TABLE + 2 * k, 2);
        return out + 2;
    }
    if (point <= 0) { /* 0.000ddd */
        *out++ = '0';
        *out++ = '.';
        for (int z = 0; z < -point; z++) {
            *out++ = '0';
        }
        put_digits(out, m, n);
        return out + n;
    }
    if (point < n) { /* ddd.ddd */
        put_digits(out + 1, m, n);
        for (int i = 0; i < point; i++) {
            out[i] = out[i + 1];
        }
        out[point] = '.';
        return out + n + 1;
    }
    put_digits(out, m, n); /* ddd000.0 */
    out += n;
    for (int z = 0; z < point - n; z++) {
        *out++ = '0';
    }
    memcpy(out, ".0", 2);
    return out + 2;
}

static void release(segment_t *segs, Py_ssize_t count, Py_ssize_t n) {
    for (Py_ssize_t s = 0; s < count; s++) {
        segment_t *g = &segs[s];
        if (g->held != NULL) {
            for (Py_ssize_t i = 0; i < n; i++) {
                Py_XDECREF(g->held[i]);
            }
            PyMem_Free(g->held);
        }
        PyMem_Free(g->texts);
        if (g->has_view) {
            PyBuffer_Release(&g->view);
        }
        if (g->has_view2) {
            PyBuffer_Release(&g->view2);
        }
    }
    PyMem_Free(segs);
}

/* a C-contiguous one-dimensional buffer of n items of the given size, or -1 with an exception */
static int take_buffer(Py_buffer *view, int *has_view, PyObject *obj, Py_ssize_t itemsize, const char *formats,
                       Py_ssize_t n, Py_ssize_t index, const char *what) {
    if (PyObject_GetBuffer(obj, view, PyBUF_C_CONTIGUOUS | PyBUF_FORMAT) < 0) {
        return -1;
    }
    *has_view = 1;
    const char *format = view->format == NULL ? "B" : view->format;
    if (format[0] == '=' || format[0] == '@' || format[0] == '<') {
        format++;
    }
    if (view->itemsize != itemsize || format[0] == '\0' || format[1] != '\0' || strchr(formats, format[0]) == NULL) {
        PyErr_Format(PyExc_TypeError, "segment %zd: %s must be a buffer of %zd-byte items ('%s'), not '%s'", index,
                     what, itemsize, formats, view->format == NULL ? "B" : view->format);
        return -1;
    }
    if (view->len / itemsize != n) {
        PyErr_Format(PyExc_ValueError, "segment %zd has %zd rows, not %zd", index, view->len / itemsize, n);
        return -1;
    }
    return 0;
}

/* segment g read from item, and in *size the most its n rows can take (texts and constants exactly, a code the
 * longest of its table, a float its bound) */
static int prepare(segment_t *g, PyObject *item, Py_ssize_t n, Py_ssize_t index, Py_ssize_t *size) {
    if (PyBytes_Check(item)) {
        g->kind = SEG_CONSTANT;
        g->constant.ptr = PyBytes_AS_STRING(item);
        g->constant.len = PyBytes_GET_SIZE(item);
        *size = g->constant.len * n;
        return 0;
    }
    if (PyList_Check(item)) {
        g->kind = SEG_TEXTS;
        if (PyList_GET_SIZE(item) != n) {
            PyErr_Format(PyExc_ValueError, "segment %zd has %zd rows, not %zd", index, PyList_GET_SIZE(item), n);
            return -1;
        }
        g->texts = PyMem_Malloc(sizeof(text_t) * (size_t)(n ? n : 1));
        g->held = PyMem_Calloc((size_t)(n ? n : 1), sizeof(PyObject *));
        if (g->texts == NULL || g->held == NULL) {
            PyErr_NoMemory();
            return -1;
        }
        Py_ssize_t total = 0;
        for (Py_ssize_t i = 0; i < n; i++) {
            PyObject *t = PyList_GET_ITEM(item, i);
            if (!PyBytes_Check(t)) {
                PyErr_Format(PyExc_TypeError, "segment %zd, row %zd: a text must be bytes, not %.100s", index, i,
                             Py_TYPE(t)->tp_name);
                return -1;
            }
            Py_INCREF(t);
            g->held[i] = t;
            g->texts[i].ptr = PyBytes_AS_STRING(t);
            g->texts[i].len = PyBytes_GET_SIZE(t);
            total += g->texts[i].len;
        }
        *size = total;
        return 0;
    }
    long tag = -1;
    if (PyTuple_Check(item) && PyTuple_GET_SIZE(item) >= 3 && PyLong_Check(PyTuple_GET_ITEM(item, 0))) {
        tag = PyLong_AsLong(PyTuple_GET_ITEM(item, 0));
    }
    if (!((tag == 0 || tag == 1) && PyTuple_GET_SIZE(item) == 3) && !(tag == 2 && PyTuple_GET_SIZE(item) == 4)) {
        PyErr_Clear();
        PyErr_Format(PyExc_TypeError,
                     "segment %zd must be bytes, a list of bytes, (0, codes, texts), (1, values, mode) or "
                     "(2, blob, starts, ends), not %.100s",
                     index, Py_TYPE(item)->tp_name);
        return -1;
    }
    if (tag == 2) {
        g->kind = SEG_SLICES;
        PyObject *blob = PyTuple_GET_ITEM(item, 1); /* the tuple holds it while the GIL is released */
        if (!PyBytes_Check(blob)) {
            PyErr_Format(PyExc_TypeError, "segment %zd: the blob must be bytes, not %.100s", index,
                         Py_TYPE(blob)->tp_name);
            return -1;
        }
        if (take_buffer(&g->view, &g->has_view, PyTuple_GET_ITEM(item, 2), (Py_ssize_t)sizeof(Py_ssize_t), "lqn", n,
                        index, "starts") < 0 ||
            take_buffer(&g->view2, &g->has_view2, PyTuple_GET_ITEM(item, 3), (Py_ssize_t)sizeof(Py_ssize_t), "lqn",
                        n, index, "ends") < 0) {
            return -1;
        }
        g->blob = PyBytes_AS_STRING(blob);
        g->starts = (const Py_ssize_t *)g->view.buf;
        g->ends = (const Py_ssize_t *)g->view2.buf;
        const Py_ssize_t length = PyBytes_GET_SIZE(blob);
        Py_ssize_t total = 0;
        for (Py_ssize_t i = 0; i < n; i++) {
            const Py_ssize_t a = g->starts[i], b = g->ends[i];
            if (a < 0 || a > b || b > length) {
                PyErr_Format(PyExc_ValueError, "segment %zd, row %zd: [%zd, %zd) is not a range of the blob's %zd bytes",
                             index, i, a, b, length);
                return -1;
            }
            total += b - a;
        }
        *size = total;
        return 0;
    }
    if (tag == 0) {
        g->kind = SEG_CODES;
        PyObject *texts = PyTuple_GET_ITEM(item, 2);
        if (!PyTuple_Check(texts) || PyTuple_GET_SIZE(texts) == 0) {
            PyErr_Format(PyExc_TypeError, "segment %zd: the texts must be a tuple of bytes, at least one", index);
            return -1;
        }
        if (take_buffer(&g->view, &g->has_view, PyTuple_GET_ITEM(item, 1), (Py_ssize_t)sizeof(Py_ssize_t), "lqn", n,
                        index, "codes") < 0) {
            return -1;
        }
        g->codes = (const Py_ssize_t *)g->view.buf;
        g->ntexts = PyTuple_GET_SIZE(texts);
        g->texts = PyMem_Malloc(sizeof(text_t) * (size_t)g->ntexts);
        if (g->texts == NULL) {
            PyErr_NoMemory();
            return -1;
        }
        Py_ssize_t longest = 0;
        for (Py_ssize_t k = 0; k < g->ntexts; k++) {
            PyObject *t = PyTuple_GET_ITEM(texts, k); /* the tuple holds them while the GIL is released */
            if (!PyBytes_Check(t)) {
                PyErr_Format(PyExc_TypeError, "segment %zd, text %zd: must be bytes, not %.100s", index, k,
                             Py_TYPE(t)->tp_name);
                return -1;
            }
            g->texts[k].ptr = PyBytes_AS_STRING(t);
            g->texts[k].len = PyBytes_GET_SIZE(t);
            if (g->texts[k].len > longest) {
                longest = g->texts[k].len;
            }
        }
        if (n && longest > PY_SSIZE_T_MAX / n) {
            PyErr_NoMemory();
            return -1;
        }
        *size = longest * n;
        return 0;
    }
    g->kind = SEG_FLOATS;
    g->mode = (int)PyLong_AsLong(PyTuple_GET_ITEM(item, 2));
    if (g->mode != MODE_CSV && g->mode != MODE_JSON) {
        if (!PyErr_Occurred()) {
            PyErr_Format(PyExc_ValueError, "segment %zd: mode must be 0 (CSV) or 1 (JSON)", index);
        }
        return -1;
    }
    if (take_buffer(&g->view, &g->has_view, PyTuple_GET_ITEM(item, 1), (Py_ssize_t)sizeof(double), "d", n, index,
                    "values") < 0) {
        return -1;
    }
    g->values = (const double *)g->view.buf;
    *size = FLOAT_MAX * n;
    return 0;
}

/* the rows written at out; -1 (and *bad the segment) where a code is outside its table */
static char *put_rows(const segment_t *segs, Py_ssize_t count, Py_ssize_t n, char *out, Py_ssize_t *bad) {
    for (Py_ssize_t i = 0; i < n; i++) {
        for (Py_ssize_t s = 0; s < count; s++) {
            const segment_t *g = &segs[s];
            const text_t *t;
            switch (g->kind) {
            case SEG_CONSTANT:
                t = &g->constant;
                break;
            case SEG_TEXTS:
                t = &g->texts[i];
                break;
            case SEG_SLICES:
                memcpy(out, g->blob + g->starts[i], (size_t)(g->ends[i] - g->starts[i]));
                out += g->ends[i] - g->starts[i];
                continue;
            case SEG_CODES: {
                const Py_ssize_t k = g->codes[i];
                if (k < 0 || k >= g->ntexts) {
                    *bad = s;
                    return NULL;
                }
                t = &g->texts[k];
                break;
            }
            default:
                out = put_float(out, g->values[i], g->mode);
                continue;
            }
            memcpy(out, t->ptr, (size_t)t->len);
            out += t->len;
        }
    }
    return out;
}

static PyObject *rowwriter_write(PyObject *self, PyObject *args) {
    (void)self;
    PyObject *layout;
    Py_ssize_t n, drop;
    if (!PyArg_ParseTuple(args, "O!nn:write", &PyList_Type, &layout, &n, &drop)) {
        return NULL;
    }
    if (n < 0 || drop < 0) {
        PyErr_SetString(PyExc_ValueError, "n and drop must not be negative");
        return NULL;
    }
    const Py_ssize_t count = PyList_GET_SIZE(layout);
    segment_t *segs = PyMem_Calloc((size_t)(count ? count : 1), sizeof(segment_t));
    if (segs == NULL) {
        return PyErr_NoMemory();
    }
    Py_INCREF(layout); /* its items stay referenced while the GIL is released */
    PyObject *result = NULL;
    Py_ssize_t bound = 0;
    for (Py_ssize_t s = 0; s < count; s++) {
        Py_ssize_t size = 0;
        if (prepare(&segs[s], PyList_GET_ITEM(layout, s), n, s, &size) < 0) {
            goto done;
        }
        if (size > PY_SSIZE_T_MAX - bound) {
            PyErr_NoMemory();
            goto done;
        }
        bound += size;
    }
    result = PyBytes_FromStringAndSize(NULL, bound);
    if (result == NULL) {
        goto done;
    }
    char *start = PyBytes_AS_STRING(result);
    char *end;
    Py_ssize_t bad = -1;
    Py_BEGIN_ALLOW_THREADS
    end = put_rows(segs, count, n, start, &bad);
    Py_END_ALLOW_THREADS
    if (end == NULL) {
        PyErr_Format(PyExc_ValueError, "segment %zd: a code outside its table of texts", bad);
        Py_CLEAR(result);
        goto done;
    }
    Py_ssize_t length = end - start;
    if (drop > length) {
        drop = length;
    }
    if (drop) {
        memmove(start, start + drop, (size_t)(length - drop));
    }
    _PyBytes_Resize(&result, length - drop); /* on failure result is NULL with the exception set */
done:
    release(segs, count, n);
    Py_DECREF(layout);
    return result;
}

static PyMethodDef methods[] = {
    {"write", rowwriter_write, METH_VARARGS,
     "write(layout, n, drop) -> bytes: n rows of the segments of layout, less the first drop bytes "
     "(app.formats.segments.write_rows)."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_rowwriter", "Rows of text from segments, in C (app.formats.segments).", -1, methods,
    NULL, NULL, NULL, NULL,
};

PyMODINIT_FUNC PyInit__rowwriter(void) { return PyModule_Create(&module); }
