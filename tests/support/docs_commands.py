#!/usr/bin/env python3
"""Every short command the documentation shows runs as written.

usage: docs_commands.py REPO_ROOT BUILD_DIR

Reads the ```sh blocks of README.md and docs/**/*.md, and runs each command line (a line ending
in "\\" goes on on the next) with bash, in the order the page gives them, in a directory of the
page's own: there `build` is BUILD_DIR and every other top-level entry is a copy of the tree,
so a command that writes into the tree changes no tracked file
and `out/...` starts empty. A command that takes minutes, needs a cluster, LAMMPS or a display,
or follows one that does, must say so at its end: `# long...` or `# interactive...`; it is
counted, not run. Any other command that fails, or runs past TIMEOUT_S, fails the test, named
with its page and line. The README's first block is the install, build and whole test suite:
CI runs it itself (.ci/run), so it is not run here. Without ParaView (`pvbatch`, installed by
`scripts/setup --tests`) scripts/render and scripts/replay are counted as not run, as the test
`io_render_views` skips itself.
"""
import glob
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

TIMEOUT_S = 180
NOT_RUN = re.compile(r"#\s*(long|interactive)\b")
PARAVIEW = re.compile(r"\bscripts/(render|replay)\b")


def pages(root):
    found = ["README.md"] + sorted(glob.glob("docs/**/*.md", root_dir=root, recursive=True))
    return [p for p in found if os.path.isfile(os.path.join(root, p))]


def commands(text):
    """(line, command) of every ```sh block, the README's first block excepted by the caller."""
    blocks, block, fenced, pending = [], None, False, None
    for number, line in enumerate(text.split("\n"), 1):
        stripped = line.strip()
        if stripped.startswith("```"):
            if not fenced and stripped[3:].strip() == "sh":
                block = []
            elif fenced and block is not None:
                blocks.append(block)
                block = None
            fenced = not fenced
            continue
        if block is None:
            continue
        if pending:
            pending = (pending[0], pending[1] + "\n" + line)
        elif stripped and not stripped.startswith("#"):
            pending = (number, line)
        if pending and not line.rstrip().endswith("\\"):
            block.append(pending)
            pending = None
    return blocks


def workspace(tree, build_dir, where):
    os.makedirs(where)
    for entry in os.listdir(tree):
        os.symlink(os.path.join(tree, entry), os.path.join(where, entry))
    os.symlink(build_dir, os.path.join(where, "build"))


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.split("\n\n")[1])
    root, build_dir = (os.path.abspath(a) for a in sys.argv[1:])
    env = dict(os.environ)
    # Open MPI as root in CI containers, and more ranks than this machine's cores: the pages'
    # mpirun lines are written for a user's machine or a node.
    env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    failed, ran, skipped = [], 0, 0
    paraview = shutil.which("pvbatch") is not None
    with tempfile.TemporaryDirectory(prefix="docs_commands.") as tmp:
        tree = os.path.join(tmp, "tree")
        os.makedirs(tree)
        for entry in os.listdir(root):
            if entry.startswith(".") or entry in ("build", "out"):
                continue
            source = os.path.join(root, entry)
            if os.path.isdir(source):
                shutil.copytree(source, os.path.join(tree, entry), symlinks=True)
            else:
                shutil.copy2(source, os.path.join(tree, entry))
        for page in pages(root):
            blocks = commands(open(os.path.join(root, page), encoding="utf-8").read())
            if page == "README.md":
                blocks = blocks[1:]
            where = os.path.join(tmp, page.replace("/", "_"))
            workspace(tree, build_dir, where)
            for number, command in (c for b in blocks for c in b):
                if NOT_RUN.search(command.split("\n")[-1]) or (
                        not paraview and PARAVIEW.search(command)):
                    skipped += 1
                    continue
                ran += 1
                start = time.monotonic()
                # A session of its own, so that a command past its time is ended with all it
                # started (mpirun's ranks, a script's runs), not only its shell.
                child = subprocess.Popen(["bash", "-c", command], cwd=where, env=env,
                                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                         text=True, start_new_session=True)
                try:
                    output = child.communicate(timeout=TIMEOUT_S)[0]
                    status = child.returncode
                except subprocess.TimeoutExpired:
                    os.killpg(child.pid, signal.SIGKILL)
                    status, output = "timeout", child.communicate()[0]
                seconds = time.monotonic() - start
                print(f"{page}:{number}: {status} in {seconds:.1f} s: {command.strip()}", flush=True)
                if status != 0:
                    why = (f"ran past {TIMEOUT_S} s: mark it `# long`" if status == "timeout"
                           else f"exit {status}")
                    failed.append(f"{page}:{number}: {why}: {command.strip()}\n"
                                  + "\n".join("    " + l for l in output.strip().split("\n")[-5:]))
    for f in failed:
        print("FAILED " + f)
    print(f"docs_commands: {ran} commands run, {skipped} marked long or interactive"
          f"{'' if paraview else ' or needing ParaView'}, "
          f"{len(failed)} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
