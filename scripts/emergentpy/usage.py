"""Every script answers -h and --help with its docstring (what it does, its usage, its exit
codes) and exit status 0, before it reads anything."""
import sys


def answer_help(doc):
    """Prints `doc` and exits 0 where the first argument asks for help."""
    if sys.argv[1:2] in (["-h"], ["--help"]):
        print(doc.strip())
        sys.exit(0)
