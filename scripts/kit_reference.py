#!/usr/bin/env python3
"""Writes the shadow-map kit's reference (docs/kit_reference.md) from its
headers, the files installed as <prefix>/include/shadowbench/common/, so that
it cannot drift from them:
  - each header's opening comment (what the kit guarantees there);
  - every class, struct, enum, function and constant its namespace declares,
    with the `//` comment block directly above it (declarations with no
    blank line between them share the block above the first); a class shows
    its public and protected members, inline bodies left out;
  - every GLSL function, uniform and global defined in an R"glsl( ... )glsl"
    string of those headers, with the `//` comment block directly above it
    inside the string.
A comment's first line says what the thing computes; lines starting with
`units:` and `cost:` give its units and cost. A declaration without a
comment block, or a pass-level class (one with a render, draw or apply
member) or a function taking FrameInputs without a `cost:` line, is refused:
the reference is complete or not written.

  kit_reference.py HEADER_DIR                  prints the reference
  kit_reference.py HEADER_DIR --out FILE       writes it
  kit_reference.py HEADER_DIR --check FILE     exit 1 naming the first line
                                               where FILE differs
  kit_reference.py --self-test                 the parser on made-up headers
"""
import argparse
import os
import re
import sys
import tempfile

GLSL_STRING = re.compile(r'R"glsl\((.*?)\)glsl"', re.S)
ANY_RAW_STRING = re.compile(r'R"([^(\s]*)\((.*?)\)\1"', re.S)
PASS_MEMBER = re.compile(r"\b(render|draw|apply)\s*\(")


class Problem(Exception):
    pass


class Entry:
    def __init__(self, kind, name, code, comment, line, glsl=None):
        self.kind, self.name, self.code = kind, name, code
        self.comment, self.line, self.glsl = comment, line, glsl

    def summary(self):
        text = " ".join(l.strip() for l in self.comment
                        if not re.match(r"\s*(units|cost):", l)).strip()
        m = re.match(r"(.+?[.])(\s|$)", text)
        text = m.group(1) if m else text
        return text if len(text) <= 140 else text[:139].rstrip() + "…"


def blank_out(text, pattern):
    """`text` with every match of `pattern` replaced by spaces and its
    newlines: offsets and line numbers are kept."""
    return pattern.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)


def code_only(text):
    """Comments and string literals blanked, for finding braces and ends."""
    text = blank_out(text, ANY_RAW_STRING)
    text = blank_out(text, re.compile(r'"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])\''))
    return blank_out(text, re.compile(r"//[^\n]*|/\*.*?\*/", re.S))


def line_of(text, offset):
    return text.count("\n", 0, offset)


def comment_above(lines, first, last_end_line):
    """The `//` block directly above line `first`, or None when the line
    above is code that ended the previous declaration (a group)."""
    block = []
    i = first - 1
    # A #define under its #ifndef guard: the block above the guard.
    while i >= 0 and re.match(r"\s*#\s*if", lines[i]) and lines[first].lstrip().startswith("#"):
        i -= 1
    while i >= 0 and lines[i].strip().startswith("//"):
        block.insert(0, lines[i].strip()[2:].removeprefix(" "))
        i -= 1
    if not block and i >= 0 and lines[i].strip() and i == last_end_line:
        return None
    return block


def matching_brace(code, open_at):
    depth = 0
    for i in range(open_at, len(code)):
        if code[i] == "{":
            depth += 1
        elif code[i] == "}":
            depth -= 1
            if depth == 0:
                return i
    raise Problem(f"unbalanced braces from offset {open_at}")


def declarations(text, where, glsl=False, macro_comment=None):
    """Top-level declarations of `text` (inside namespaces for C++): Entry
    objects in file order. A #define without a comment of its own (a guarded
    default, `#ifndef N` / `#define N 64`) takes `macro_comment`, its GLSL
    string's."""
    code = code_only(text)
    lines = text.split("\n")
    out, i, start, last_end_line, group_comment, parens = [], 0, None, -2, [], 0
    while i < len(code):
        c = code[i]
        if start is not None and c in "()":
            parens += 1 if c == "(" else -1
        if start is not None and c == "{" and parens > 0:  # a default argument's braces
            i = matching_brace(code, i) + 1
            continue
        if start is None:
            parens = 0
            if c.isspace():
                i += 1
                continue
            if c == "}":  # a namespace closes
                i += 1
                continue
            if c == "#":  # preprocessor line
                end = code.find("\n", i)
                end = len(code) if end < 0 else end
                directive = text[i:end]
                m = re.match(r"#\s*define\s+(\w+)", directive)
                if m:
                    out.append(_entry("macro", m.group(1), directive, lines, i, text,
                                      last_end_line, group_comment or macro_comment, where,
                                      glsl))
                    group_comment = out[-1].comment
                    last_end_line = line_of(text, end)
                i = end
                continue
            start = i
        if c == ";":
            statement = text[start:i + 1]
            entry = _statement_entry(statement, None, lines, start, text, last_end_line,
                                     group_comment, where, glsl)
            if entry:
                out.append(entry)
                group_comment = entry.comment
            last_end_line = line_of(text, i)
            start, i = None, i + 1
            continue
        if c == "{":
            head = code[start:i]
            if re.match(r"\s*(inline\s+)?namespace\b", head):
                start, i = None, i + 1
                continue
            close = matching_brace(code, i)
            end = close + 1
            m = re.match(r"\s*;", code[end:])
            if m:
                end += m.end()
            # Only declarations without a body group: one with a body (a
            # class, an enum, a function) has a block of its own.
            entry = _statement_entry(text[start:end], text[start:i], lines, start, text,
                                     last_end_line, [], where, glsl, body=text[i + 1:close])
            if entry:
                out.append(entry)
            group_comment = []
            last_end_line = line_of(text, end - 1)
            start, i = None, end
            continue
        i += 1
    return out


def _entry(kind, name, code, lines, offset, text, last_end_line, group_comment, where, glsl):
    first = line_of(text, offset)
    comment = comment_above(lines, first, last_end_line)
    if comment is None or (not comment and kind == "macro"):
        comment = group_comment
    if not comment:
        raise Problem(f"{where}:{first + 1}: {kind} {name} has no // comment block directly "
                      f"above it (what it computes, then units: and cost: lines)")
    return Entry(kind, name, code, comment, first + 1, glsl)


def _statement_entry(statement, head, lines, offset, text, last_end_line, group_comment, where,
                     glsl, body=None):
    flat = " ".join(code_only(head if head is not None else statement).split())
    if not flat or flat.startswith(("using ", "static_assert", "template <> ")) or flat == ";":
        return None
    if glsl and re.match(r"(precision|#)", flat):
        return None
    kind, name, code = None, None, statement.strip()
    m = re.match(r"(?:template\s*<[^>]*>\s*)?(class|struct|enum class|enum)\s+(\w+)", flat)
    if m and (body is not None or glsl):
        kind, name = m.group(1), m.group(2)
        if kind in ("class", "struct") and not glsl:
            code = class_synopsis(head.strip(), body, kind)
    elif "(" in flat and not re.search(r"=\s*R?\"", flat) and \
            re.match(r"[\w:<>,*&\s\[\]]+\(", flat) and not flat.startswith("layout"):
        kind = "function"
        name = re.match(r"[\w:<>,*&\s\[\]]*?(~?[\w:]+|operator\S+)\s*\(", flat).group(1)
        code = head.strip() + ";" if head is not None else statement.strip()
        code = re.sub(r"\)\s*:\s*[^;]*;$", ");", code) if head is not None else code
    else:
        declarator = re.sub(r"^layout\s*\([^)]*\)\s*", "", flat)
        words = re.findall(r"[A-Za-z_]\w*", declarator.split("=")[0].split("{")[0])
        kind, name = ("uniform" if "uniform" in words else "variable"), words[-1]
        if "R\"glsl(" in statement or GLSL_STRING.search(statement):
            kind = "GLSL"
            code = GLSL_STRING.sub('R"glsl(...)glsl"', statement.strip())
    return _entry(kind, name, code, lines, offset, text, last_end_line, group_comment, where,
                  glsl)


def class_synopsis(head, body, kind):
    """The class as its users see it: public and protected members, inline
    function bodies and private sections left out."""
    code = code_only(body)
    kept, i, access, piece_start = [], 0, "private" if kind == "class" else "public", 0
    pieces = []  # (access, text)
    while i < len(code):
        m = re.compile(r"\b(public|protected|private)\s*:(?!:)").match(code, i)
        if m and (i == 0 or not (code[i - 1].isalnum() or code[i - 1] == "_")) and \
                code[:i].count("{") == code[:i].count("}"):
            pieces.append((access, body[piece_start:i]))
            access, piece_start = m.group(1), m.end()
            if m.group(1) == "protected":
                pieces.append(("protected", "\n protected:"))
            i = m.end()
            continue
        if code[i] == "{":
            close = matching_brace(code, i)
            before = code[piece_start:i].rstrip()
            if re.search(r"(\)|\bconst|\boverride|\bnoexcept|\bfinal)$", before):
                signature = body[piece_start:i].rstrip()
                # A constructor's initializer list goes with its body.
                depth, cut = 0, None
                for j, ch in enumerate(code[piece_start:i]):
                    depth += {"(": 1, ")": -1}.get(ch, 0)
                    if ch == ":" and depth == 0 and code[piece_start + j + 1] != ":" and \
                            code[piece_start + j - 1] != ":":
                        cut = j
                        break
                if cut is not None:
                    signature = body[piece_start:piece_start + cut].rstrip()
                pieces.append((access, signature + ";"))
                piece_start = close + 1
                i = close + 1
                continue
            i = close + 1
            continue
        i += 1
    pieces.append((access, body[piece_start:]))
    for access, text in pieces:
        if access != "private":
            kept.append(text)
    lines = [l.rstrip() for l in "".join(kept).split("\n")]
    out = []
    for l in lines:
        if l.strip() or (out and out[-1].strip()):
            out.append(l)
    while out and not out[-1].strip():
        out.pop()
    if kind == "class" and out and out[0].strip() not in ("public:", "protected:"):
        out.insert(0, " public:")
    return head + " {\n" + "\n".join(out) + "\n};"


def header_comment(text):
    lines = text.split("\n")
    i = 1 if lines and lines[0].startswith("#pragma once") else 0
    block = []
    while i < len(lines) and lines[i].startswith("//"):
        block.append(lines[i])
        i += 1
    return block


def read_header(path, name):
    with open(path) as f:
        text = f.read()
    where = f"common/{name}"
    entries = declarations(text, where)
    for e in entries:
        if e.kind in ("class", "struct") and PASS_MEMBER.search(e.code) or \
                e.kind == "function" and "FrameInputs" in e.code:
            if not any(l.startswith("cost:") for l in e.comment):
                raise Problem(f"{where}:{e.line}: {e.kind} {e.name} draws or renders but its "
                              f"comment has no cost: line")
    glsl = []
    for m in GLSL_STRING.finditer(text):
        owner = [e for e in entries if e.kind == "GLSL" and e.line - 1 <=
                 line_of(text, m.start()) and m.group(1) in text[m.start():m.end()]]
        owner_name = owner[-1].name if owner else "?"
        first_line = line_of(text, m.start(1))
        body = m.group(1)
        try:
            for e in declarations(body, f"{where} ({owner_name})", glsl=True,
                                  macro_comment=owner[-1].comment if owner else None):
                e.line += first_line
                e.glsl = owner_name
                glsl.append(e)
        except Problem as p:
            message = str(p)
            n = re.search(r":(\d+): ", message)
            if n:
                message = message.replace(f":{n.group(1)}: ",
                                          f":{int(n.group(1)) + first_line}: ", 1)
            raise Problem(message) from None
    return header_comment(text), entries, glsl


def anchor(header, name):
    return re.sub(r"[^a-z0-9_-]", "", f"{header}-{name}".lower().replace("/", "-")
                  .replace(".", "-"))


def render(header_dir):
    names = sorted(f for f in os.listdir(header_dir) if f.endswith(".h"))
    if not names:
        raise Problem(f"{header_dir}: no headers")
    parsed = [(n, *read_header(os.path.join(header_dir, n), n)) for n in names]
    out = ["# The shadow-map kit: reference", "",
           "<!-- Generated by scripts/kit_reference.py from techniques/common/*.h; do not edit:",
           "     `scripts/kit_reference.py techniques/common --out docs/kit_reference.md`. -->",
           "",
           "Every class, function and GLSL helper of the shadow-map kit, as its headers",
           "declare it and with the comment above it there: the headers are installed as",
           "`<prefix>/include/shadowbench/common/` (included as `\"common/map_lookup.h\"`),",
           "the code as the static library `shadowbench::shadow_kit` (link it with",
           "`target_link_libraries(my_technique PRIVATE shadowbench::shadow_kit)`), and",
           "its names are in `sb::techniques`. This page is generated from those headers",
           "and a test compares it with them, so what it says is what they declare.",
           "",
           "Each entry's comment says what it computes first; `units:` and `cost:`",
           "lines give its units and its cost (a tap is one texture fetch). Each",
           "header's own opening comment says what the kit guarantees there: what",
           "goes in, what comes out, the GL state it leaves and its cost.",
           "",
           "GLSL helpers are strings of GLSL source a technique puts into its",
           "shaders: the ones in `kMapLookupInputsGlsl`, `kLightLookupGlsl` and",
           "`kLightDepthGlsl` are in every lookup pass, so a `lit_fraction()` of",
           "yours may call them (`common/map_lookup.h`).", "",
           "A technique built on the kit is written as",
           "[writing_a_technique.md](writing_a_technique.md)",
           "says (section 5), and `shadowbench check-technique NAME` checks it",
           "against the timing contract the built-ins keep (section 3).", "",
           "## Contents", "", "| header | name | kind | what it is |", "|---|---|---|---|"]
    for n, _, entries, glsl in parsed:
        for e in entries + glsl:
            kind = f"GLSL {e.kind} in `{e.glsl}`" if e.glsl else e.kind
            summary = e.summary().replace("|", "\\|")
            out.append(f"| `common/{n}` | [`{e.name}`](#{anchor(n, e.name)}) | {kind} | "
                       f"{summary} |")
    for n, intro, entries, glsl in parsed:
        out += ["", f"## common/{n}", ""]
        if intro:
            out += ["```cpp"] + intro + ["```", ""]
        for e in entries + glsl:
            where = f"GLSL {e.kind} in `{e.glsl}`" if e.glsl else e.kind
            out += [f'### <a id="{anchor(n, e.name)}"></a>`{e.name}` ({where})', "",
                    "```" + ("glsl" if e.glsl else "cpp")]
            out += ["// " + l if l else "//" for l in e.comment]
            out += [e.code, "```", ""]
        while out[-1] == "":
            out.pop()
    return "\n".join(out) + "\n"


def check(header_dir, path):
    want = render(header_dir)
    with open(path) as f:
        have = f.read()
    if want == have:
        return 0
    a, b = have.split("\n"), want.split("\n")
    for i in range(max(len(a), len(b))):
        x = a[i] if i < len(a) else "<end of file>"
        y = b[i] if i < len(b) else "<end of file>"
        if x != y:
            print(f"{path}:{i + 1}: differs from the headers in {header_dir}:\n"
                  f"  file:    {x}\n  headers: {y}\n"
                  f"regenerate it: scripts/kit_reference.py {header_dir} --out {path}")
            return 1
    return 1


SELF_TEST_HEADER = '''#pragma once
// A made-up kit header.
namespace sb::techniques {

// Does one thing.
// cost: O(1).
class Pass {
 public:
  // Draws.
  void draw() const { return; }
  int size() const {
    return size_;
  }

 private:
  int size_ = 0;
};
// Two in a group.
int first(int a);
int second(int b, std::vector<int> c = {});

// Shader text.
inline constexpr const char* kGlsl = R"glsl(
// A uniform.
uniform float u;
// A helper.
// units: texels.
float helper(float x) { return x * u; }
)glsl";

}  // namespace sb::techniques
'''


def self_test():
    def parse(text):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "x.h"), "w") as f:
                f.write(text)
            return render(d)

    def refused(text, why):
        try:
            parse(text)
        except Problem as p:
            if why not in str(p):
                sys.exit(f"self-test: refused for another reason: {p} (expected {why!r})")
            return
        sys.exit(f"self-test: accepted a header with {why!r}")

    doc = parse(SELF_TEST_HEADER)
    for want in ("`Pass` (class)", "void draw() const;", "int size() const;", "`second` (function)",
                 "int second(int b, std::vector<int> c = {});",
                 "`helper` (GLSL function in `kGlsl`)", "// units: texels.", "`u` (GLSL uniform"):
        if want not in doc:
            sys.exit(f"self-test: {want!r} missing from\n{doc}")
    if "size_" in doc or "return x * u" in doc:
        sys.exit(f"self-test: private members or a GLSL body in\n{doc}")
    refused(SELF_TEST_HEADER.replace("// Two in a group.\n", ""), "function first has no //")
    refused(SELF_TEST_HEADER.replace("// A helper.\n// units: texels.\n", ""),
            "x.h (kGlsl):26: function helper has no //")
    refused(SELF_TEST_HEADER.replace("// cost: O(1).\n", ""), "class Pass draws or renders")
    refused(SELF_TEST_HEADER.replace("// Shader text.\n", ""), "GLSL kGlsl has no //")
    print("kit_reference self-test: ok")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("header_dir", nargs="?")
    ap.add_argument("--out")
    ap.add_argument("--check")
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if a.self_test:
        return self_test()
    if not a.header_dir:
        ap.error("HEADER_DIR is required")
    try:
        if a.check:
            return check(a.header_dir, a.check)
        text = render(a.header_dir)
    except Problem as p:
        print(f"kit_reference: {p}", file=sys.stderr)
        return 1
    if a.out:
        with open(a.out, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
