#!/usr/bin/env python3
"""The engine stays in parts a reader can hold: src/core/simulation.cpp within 600 lines, and no
function of the engine's files (src/core/*.cpp) over 80 lines. A function is counted from the
line that opens its body at namespace level to the line that closes it, comments included.
usage: engine_size.py ROOT"""
import pathlib
import sys

MAX_FILE, MAX_FUNCTION = 600, 80


def functions(text):
    """(first line, line count, head) of each top-level brace block that is a function body."""
    depth, start, head, out = 0, None, "", []
    namespaces = 0  # namespace blocks do not count as depth
    stack = []
    for number, line in enumerate(text.split("\n"), 1):
        code = line.split("//")[0]
        for ch in code:
            if ch == "{":
                is_namespace = depth == 0 and ("namespace" in code or code.strip().startswith("struct")
                                               and code.rstrip().endswith("{") and "(" not in code)
                stack.append(is_namespace)
                if is_namespace:
                    namespaces += 1
                else:
                    if depth == 0:
                        start, head = number, line.strip()
                    depth += 1
            elif ch == "}":
                if not stack:
                    continue
                if stack.pop():
                    namespaces -= 1
                else:
                    depth -= 1
                    if depth == 0 and start is not None:
                        out.append((start, number - start + 1, head))
                        start = None
    return out


def main():
    root = pathlib.Path(sys.argv[1])
    problems = []
    sim = root / "src/core/simulation.cpp"
    n = len(sim.read_text().split("\n"))
    if n > MAX_FILE:
        problems.append(f"{sim.relative_to(root)}: {n} lines (at most {MAX_FILE})")
    for path in sorted((root / "src/core").glob("*.cpp")):
        for first, length, head in functions(path.read_text()):
            if length > MAX_FUNCTION:
                problems.append(f"{path.relative_to(root)}:{first}: a function of {length} lines "
                                f"(at most {MAX_FUNCTION}): {head[:70]}")
    for p in problems:
        print(p)
    print(f"engine_size: {len(problems)} over the limits")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
