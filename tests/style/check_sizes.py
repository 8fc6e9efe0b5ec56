#!/usr/bin/env python3
"""The product's sizes stay readable: no C++ function of the product (base/, noise/, volume/,
render/, samples/, python/src/) over 150 lines, and no samples/ source file over 400 lines.

A function is a definition that starts at the first column (nimbus does not indent namespaces)
and ends at its matching brace; braces inside strings, characters and comments are skipped.
Prints each offender with its length and exits 1 if there is one.
Usage: check_sizes.py ROOT, or check_sizes.py --self-test (the checker on trees made to fail and pass)."""
import pathlib
import re
import sys

FUNCTION_LIMIT = 150
SAMPLES_FILE_LIMIT = 400
PRODUCT = ("base", "noise", "volume", "render", "samples", "python/src")
NOT_A_FUNCTION = re.compile(r"^(namespace|struct|class|enum|union|extern|template\s*<[^>]*>\s*(struct|class))\b")


def code_only(text: str) -> str:
    """The text with comments, strings and character literals blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            end = j + 1 if j < n and text[j] == c else j  # an unclosed quote ends at its line
            out.append(" " * (end - i))
            i = end
        else:
            out.append(c)
            i += 1
    return "".join(out)


def long_functions(path: pathlib.Path):
    lines = code_only(path.read_text(errors="replace")).split("\n")
    i = 0
    while i < len(lines):
        line = lines[i]
        start = i
        # A definition's head: first column, not a keyword of a type or namespace; its body's
        # brace on this line or on one of the next few (a head folded over lines).
        if line[:1] and (line[:1].isalpha() or line[:1] in "_~"):
            head = line
            j = i
            while "{" not in lines[j] and ";" not in lines[j] and j - i < 6 and j + 1 < len(lines):
                j += 1
                head += " " + lines[j]
            if "{" in lines[j] and "(" in head and not NOT_A_FUNCTION.match(head.strip()) and "=" not in head.split("(")[0]:
                depth, k = 0, j
                for k in range(j, len(lines)):
                    depth += lines[k].count("{") - lines[k].count("}")
                    if depth <= 0 and k >= j:
                        break
                length = k - start + 1
                if length > FUNCTION_LIMIT:
                    yield start + 1, length, head.strip()[:80]
                i = k + 1
                continue
        i += 1


def main(root: str) -> int:
    base = pathlib.Path(root)
    bad = []
    for folder in PRODUCT:
        for path in sorted((base / folder).rglob("*.cpp")) + sorted((base / folder).rglob("*.hpp")):
            rel = path.relative_to(base)
            for line, length, head in long_functions(path):
                bad.append(f"{rel}:{line}: a function of {length} lines (at most {FUNCTION_LIMIT}): {head}")
            if folder == "samples":
                n = path.read_text(errors="replace").count("\n")
                if n > SAMPLES_FILE_LIMIT:
                    bad.append(f"{rel}: {n} lines (a samples/ file holds at most {SAMPLES_FILE_LIMIT})")
    for b in bad:
        print(b)
    return 1 if bad else 0


def self_test() -> int:
    """The checker finds a 151-line function and a 401-line samples/ file, and passes the same
    tree cut to the limits (a brace in a string or comment does not end a function)."""
    import tempfile

    def tree(function_lines: int, file_lines: int) -> str:
        root = tempfile.mkdtemp(prefix="nimbus-sizes-")
        body = ['  s += "}";  // }'] * (function_lines - 2)
        (pathlib.Path(root) / "render").mkdir()
        (pathlib.Path(root) / "render" / "f.cpp").write_text("\n".join(["int f(int x) {"] + body + ["}"]) + "\n")
        (pathlib.Path(root) / "samples").mkdir()
        (pathlib.Path(root) / "samples" / "g.cpp").write_text("int y;\n" * file_lines)
        return root

    found = main(tree(FUNCTION_LIMIT + 1, SAMPLES_FILE_LIMIT + 1))
    passed = main(tree(FUNCTION_LIMIT, SAMPLES_FILE_LIMIT))
    print(f"oversized tree: exit {found} (want 1); tree at the limits: exit {passed} (want 0)")
    return 0 if (found, passed) == (1, 0) else 1


if __name__ == "__main__":
    if sys.argv[1:] == ["--self-test"]:
        sys.exit(self_test())
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
