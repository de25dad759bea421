"""checks.py - what the Python test scripts share: checks that are counted
instead of stopping at the first, and the exit status CTest reads.

A script finds this file through its own path:

    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "common"))
    from checks import check, finish
"""
import sys

failures = 0


def check(cond, what):
    """Counts a failed check and prints what failed; returns cond."""
    global failures
    if not cond:
        failures += 1
        print("FAIL:", what)
    return cond


def finish(name):
    """Prints the failure count under name and exits 1 if any check failed."""
    print("%s: %d failure(s)" % (name, failures))
    sys.exit(1 if failures else 0)


def use_debian_pyelftools():
    """Makes Debian's python3-pyelftools importable from a python3 of its own
    (pyenv) that does not search Debian's dist-packages."""
    try:
        import elftools  # noqa: F401
    except ImportError:
        sys.path.append("/usr/lib/python3/dist-packages")
