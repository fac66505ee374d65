"""same(a, b, path, fail): two JSON values compared recursively, for the
install suite's Python checks (test_python.py, test_pip.sh): the same keys,
lengths, strings and integers; numbers within a relative 1e-12 (the package
and the program run the same library code, so they agree to rounding or
better).  Each difference is passed to fail(message) with its path."""


def same(a, b, path, fail):
    if isinstance(a, dict) and isinstance(b, dict):
        if set(a) != set(b):
            fail("%s: keys differ: %s" % (path, sorted(set(a) ^ set(b))))
        for k in set(a) & set(b):
            same(a[k], b[k], path + "." + k, fail)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            fail("%s: lengths %d vs %d" % (path, len(a), len(b)))
        for i, (x, y) in enumerate(zip(a, b)):
            same(x, y, "%s[%d]" % (path, i), fail)
    elif isinstance(a, float) or isinstance(b, float):
        if not (isinstance(a, (int, float)) and isinstance(b, (int, float))
                and abs(a - b) <= 1e-12 * max(abs(a), abs(b), 1e-300)):
            fail("%s: %r vs %r" % (path, a, b))
    elif a != b:
        fail("%s: %r vs %r" % (path, a, b))
