#!/usr/bin/env python3
"""Wrap every line of the C# code longer than .editorconfig's max_line_length (140) without changing what it compiles to.

    usage: scripts/wrap-lines.py [--check] [--limit N] [PATH ...]

PATHs default to src/ and tests/ of the repository this script lives in; every *.cs file below them is rewritten in
place, except under bin/, obj/, node_modules/ and tests/corpus/ (the bad-input corpus). Columns are counted as
.ci/run's grep and LineLengthTests count them: characters (Unicode scalar values). Only lines longer than the limit
change, so a second run changes nothing. --check rewrites nothing and exits 1 when a file would change. The script
uses Python 3's standard library only. On a tree to wrap (e.g. after a merge), from the repository's root:

    python3 scripts/wrap-lines.py            # wraps; lists the lines left for a hand fix (exit 2 if any)
    dotnet format SpectralRenderer.sln       # lays out the object initialisers it broke, one member a line
    python3 scripts/wrap-lines.py --check    # nothing more to change, no line left over 140

then build, run the tests and scripts/same-pictures.sh: wrapping changes no compiled behaviour.

What it does with a long line:
  * `//` and `///` comment lines: the words flow onto a continuation line with the same indentation and prefix,
    merged into the next line of the same paragraph when there is one. A break is only at a space, never inside an
    XML tag (`<see cref="..."/>`), a `code span` or a URL.
  * A trailing `// comment` after code moves onto its own line above the code.
  * Code breaks at the outermost bracket depth that has a break point, by preference: after an attribute section
    or an if/for/foreach/while/using header (the statement goes on the next line), after `;`, after `=` (when the
    right side then fits), after `,`, after `=>` (as the code writes it), before `?` and `:` of a conditional, before `??`, `||`, `&&`,
    binary `+`/`-`, before `.Method(` after a call in a chain, and last after an opening `(`. Commas and operators
    fill each line as far as they fit (the operators start the continuation lines, as the rest of the code does);
    continuation lines are indented 4 columns deeper than the line they continue. A piece still too long is wrapped
    the same way inside.
  * A string literal that alone keeps a line too long is split at a space into `"..."` + `"..."` (interpolated ones
    into `$"..."` + `$"..."`, never inside a hole), only where the concatenation means the same (the literal stands
    between `(`, `,`, `=`, `+`, `:` ... and `)`, `,`, `;`, `+` ...). Constant strings stay constants. Verbatim,
    raw and UTF-8 literals are never split, nor is any literal, character or comment broken inside.
  * A line it cannot wrap safely (a line inside a multi-line literal or comment, a preprocessor line, a piece with
    no break point) is left as it is and reported as file:line; the script then exits 2 so it can be wrapped by hand.
"""
import os
import re
import sys

LIMIT = 140
STEP = 4

OPERATORS = sorted(['>>>=', '>>=', '<<=', '??=', '=>', '==', '!=', '<=', '>=', '&&', '||', '??', '?.', '++', '--',
                    '+=', '-=', '*=', '/=', '%=', '&=', '|=', '^=', '<<', '->', '::', '..'], key=len, reverse=True)
ASSIGNMENTS = {'=', '+=', '-=', '*=', '/=', '%=', '&=', '|=', '^=', '??=', '<<=', '>>=', '>>>='}
HEADERS = {'if', 'while', 'for', 'foreach', 'using', 'lock', 'fixed'}
STRING_START = re.compile(r'(\$*)(@?)(\$*)"')
NUMBER = re.compile(r'0[xXbB][0-9A-Fa-f_]+[uUlL]*|(\d[\d_]*)?\.?\d[\d_]*([eE][+-]?\d+)?[fFdDmMuUlL]*')
# Where a string literal may become `"a" + "b"` with the same meaning: between these tokens.
SAFE_BEFORE = {'(', ',', '=', '+', 'return', '=>', '?', ':', '??', '[', '{', '+='}
SAFE_AFTER = {',', ')', ';', ']', '}', '+', ':', '??'}


class Token:
    __slots__ = ('kind', 'start', 'end', 'sub', 'holes')

    def __init__(self, kind, start, end, sub=None, holes=()):
        self.kind, self.start, self.end, self.sub, self.holes = kind, start, end, sub, holes


# ---------------------------------------------------------------------------------------------------------- lexer

def string_end(src, i):
    """End of the string literal starting at i, its kind and the spans of its interpolation holes."""
    m = STRING_START.match(src, i)
    dollars, verbatim = len(m.group(1)) + len(m.group(3)), bool(m.group(2))
    j = m.end() - 1
    q = 0
    while j + q < len(src) and src[j + q] == '"':
        q += 1
    holes = []
    if q >= 3 and not verbatim:
        close = src.find('"' * q, j + q)
        k = len(src) if close < 0 else close + q
        sub = 'raw'
    else:
        k = j + 1
        while k < len(src):
            ch = src[k]
            if verbatim and ch == '"':
                if src.startswith('""', k):
                    k += 2
                    continue
                k += 1
                break
            if not verbatim:
                if ch == '\\':
                    k += 2
                    continue
                if ch == '"':
                    k += 1
                    break
                if ch == '\n':
                    break
            if dollars and ch in '{}':
                if src.startswith(ch * 2, k):
                    k += 2
                    continue
                if ch == '{':
                    h = hole_end(src, k + 1)
                    holes.append((k, h))
                    k = h
                    continue
            k += 1
        sub = 'verbatim' if verbatim else ('interp' if dollars else 'plain')
    if src.startswith(('u8', 'U8'), k):
        k += 2
        sub = 'utf8'
    return k, sub, holes


def char_end(src, i):
    k = i + 1
    while k < len(src) and src[k] != "'" and src[k] != '\n':
        k += 2 if src[k] == '\\' else 1
    return k + 1


def hole_end(src, k):
    """End (after the `}`) of an interpolation hole whose code starts at k."""
    depth = 0
    while k < len(src):
        ch = src[k]
        if ch in '([{':
            depth += 1
        elif ch in ')]':
            depth -= 1
        elif ch == '}':
            if depth == 0:
                return k + 1
            depth -= 1
        elif ch in '"@$' and STRING_START.match(src, k):
            k = string_end(src, k)[0]
            continue
        elif ch == "'":
            k = char_end(src, k)
            continue
        elif ch == ':' and depth == 0 and src[k + 1:k + 2] != ':' and src[k - 1] != ':':
            e = src.find('}', k)
            return len(src) if e < 0 else e + 1
        k += 1
    return k


def lex(src):
    tokens = []
    i, n, line_start = 0, len(src), True
    while i < n:
        c = src[i]
        if c == '\n':
            tokens.append(Token('nl', i, i + 1))
            i += 1
            line_start = True
            continue
        if c in ' \t\r':
            j = i
            while j < n and src[j] in ' \t\r':
                j += 1
            tokens.append(Token('ws', i, j))
            i = j
            continue
        if line_start and c == '#':
            j = src.find('\n', i)
            j = n if j < 0 else j
            tokens.append(Token('pp', i, j))
            i = j
            continue
        line_start = False
        if src.startswith('//', i):
            j = src.find('\n', i)
            j = n if j < 0 else j
            tokens.append(Token('comment', i, j))
        elif src.startswith('/*', i):
            j = src.find('*/', i + 2)
            j = n if j < 0 else j + 2
            tokens.append(Token('block', i, j))
        elif c in '"@$' and STRING_START.match(src, i):
            j, sub, holes = string_end(src, i)
            tokens.append(Token('str', i, j, sub, holes))
        elif c == "'":
            j = char_end(src, i)
            tokens.append(Token('char', i, j))
        elif c.isalpha() or c == '_' or (c == '@' and i + 1 < n and (src[i + 1].isalpha() or src[i + 1] == '_')):
            j = i + 1
            while j < n and (src[j].isalnum() or src[j] == '_'):
                j += 1
            tokens.append(Token('id', i, j))
        elif c.isdigit() or (c == '.' and i + 1 < n and src[i + 1].isdigit()):
            m = NUMBER.match(src, i)
            j = m.end() if m and m.end() > i else i + 1
            tokens.append(Token('num', i, j))
        else:
            j = i + 1
            for op in OPERATORS:
                if src.startswith(op, i):
                    j = i + len(op)
                    break
            tokens.append(Token('op', i, j))
        i = j
    return tokens


def lex_lines(src):
    """Per line: (clean, tokens relative to the line's start); clean is False for a line that starts inside a
    multi-line literal or comment. A token running past the line's end ends at the end."""
    starts = [0] + [m.end() for m in re.finditer('\n', src)]
    lines = [[True, []] for _ in starts]
    li = 0
    for t in lex(src):
        if t.kind in ('nl', 'ws'):
            if t.kind == 'nl':
                li += 1
            continue
        while li + 1 < len(starts) and starts[li + 1] <= t.start:
            li += 1
        base = starts[li]
        eol = src.find('\n', base)
        eol = len(src) if eol < 0 else eol
        holes = tuple((a - base, b - base) for a, b in t.holes)
        lines[li][1].append(Token(t.kind, t.start - base, min(t.end, eol) - base, t.sub if t.end <= eol else 'open',
                                  holes))
        k = li
        while k + 1 < len(starts) and starts[k + 1] < t.end:
            k += 1
            lines[k][0] = False
    return lines


# ---------------------------------------------------------------------------------------------------------- code

class Piece:
    """Tokens toks[a:b] of one source line, to be laid out at a given indentation."""

    def __init__(self, line, toks, indent, before='', after=''):
        self.line, self.toks, self.indent = line, toks, indent
        self.before, self.after = before, after  # the tokens around it (on other lines too), for split_string

    def text(self, a=0, b=None):
        b = len(self.toks) if b is None else b
        return self.line[self.toks[a].start:self.toks[b - 1].end]

    def width(self, a=0, b=None, indent=None):
        return len(self.indent if indent is None else indent) + len(self.text(a, b))


def tok_text(line, t):
    return line[t.start:t.end]


def generic_spans(line, toks):
    """Indices of tokens inside a generic argument list `Name<...>` (no break there)."""
    inside = set()
    allowed = {',', '.', '?', '[', ']', '(', ')', '<', '>', '::'}
    for k, t in enumerate(toks):
        if tok_text(line, t) != '<' or k == 0 or toks[k - 1].kind != 'id' or toks[k - 1].end != t.start:
            continue
        depth, m = 0, k
        while m < len(toks):
            x = tok_text(line, toks[m])
            if x == '<':
                depth += 1
            elif x == '>':
                depth -= 1
                if depth == 0:
                    break
            elif not (toks[m].kind == 'id' or x in allowed):
                m = len(toks)
                break
            m += 1
        if m < len(toks):
            inside.update(range(k, m + 1))
    return inside


def matching(line, toks, k):
    depth = 0
    for m in range(k, len(toks)):
        x = tok_text(line, toks[m])
        if x in '([{':
            depth += 1
        elif x in ')]}':
            depth -= 1
            if depth == 0:
                return m
    return None


def spaced(line, toks, k):
    return 0 < k < len(toks) - 1 and toks[k - 1].end < toks[k].start and toks[k].end < toks[k + 1].start


# Break classes: name -> (preference, indentation step of the continuation, fill lines greedily?, condition)
CLASSES = {
    'block': (0, 0, False), 'attribute': (0, 0, False), 'statement': (1, 0, False), 'header': (2, STEP, False), 'assign': (3, STEP, False),
    'comma': (4, STEP, True), 'arrow': (5, STEP, False), 'conditional': (6, STEP, False), 'coalesce': (7, STEP, True),
    'or': (8, STEP, True), 'and': (9, STEP, True), 'additive': (10, STEP, True), 'chain': (11, STEP, True),
    'open': (13, STEP, False),
}


def candidates(p):
    """(depth, class, index of the token a new line starts with) of every break point of the piece."""
    line, toks = p.line, p.toks
    text = [tok_text(line, t) for t in toks]
    generic = generic_spans(line, toks)
    out = []
    depth, stack, opens, questions = 0, [], [], {}
    enclosing = []  # per token: the innermost bracket open around it (its index), or None
    n = len(toks)
    if text[0] == '[':
        m = matching(line, toks, 0)
        if m is not None and m + 1 < n and (toks[m + 1].kind == 'id' or text[m + 1] == '['):
            out.append((0, 'attribute', m + 1))
    for k, t in enumerate(toks):
        x = text[k]
        enclosing.append(opens[-1] if opens else None)
        if t.kind == 'op':
            if x in ')]}':
                depth -= 1
                if stack:
                    stack.pop()
                    opens.pop()
            inner = stack[-1] if stack else None
            if x in '([{':
                m = matching(line, toks, k)
                lambda_body = k > 0 and text[k - 1] == '=>'
                statement = depth == 0 and not stack and (k == 0 or text[k - 1] in (')', 'else', 'try', 'finally', 'do'))
                if x == '{' and m is not None and (lambda_body or (statement and m == n - 1)) and ';' in text[k:m]:
                    out.append((depth, 'block', k + 1))  # the line after `{`
                if x == '(' and k + 1 < n and text[k + 1] != ')':
                    out.append((depth + 1, 'open', k + 1))
                stack.append(x)
                opens.append(k)
                depth += 1
            elif x == ',' and k not in generic:
                out.append((depth, 'comma', k + 1))
            elif x == ';' and k + 1 < n and inner in (None, '('):
                out.append((depth, 'comma' if inner == '(' else 'statement', k + 1))
            elif x == '=>':
                out.append((depth, 'arrow', k + 1))
            elif x in ASSIGNMENTS and spaced(line, toks, k) and inner is None:
                out.append((depth, 'assign', k + 1))
            elif x == '?' and spaced(line, toks, k):
                questions[depth] = questions.get(depth, 0) + 1
                out.append((depth, 'conditional', k))
            elif x == ':' and spaced(line, toks, k) and questions.get(depth, 0) > 0:
                questions[depth] -= 1
                out.append((depth, 'conditional', k))
            elif x == '??' and spaced(line, toks, k):
                out.append((depth, 'coalesce', k))
            elif x == '||' and spaced(line, toks, k):
                out.append((depth, 'or', k))
            elif x == '&&' and spaced(line, toks, k):
                out.append((depth, 'and', k))
            elif x in '+-' and spaced(line, toks, k) and (toks[k - 1].kind in ('id', 'num', 'str', 'char')
                                                           or text[k - 1] in (')', ']')):
                out.append((depth, 'additive', k))
            elif x in ('.', '?.') and k > 0 and text[k - 1] in (')', ']') and k + 1 < n and toks[k + 1].kind == 'id':
                out.append((depth, 'chain', k))
        elif t.kind == 'id' and depth == 0 and not stack:
            if x in HEADERS and k + 1 < n and text[k + 1] == '(':
                m = matching(line, toks, k + 1)
                if m is not None and m + 1 < n and text[m + 1] not in ('{', ';', ')', '.', '?', '?.'):
                    out.append((0, 'header', m + 1))
            elif x == 'else' and k + 1 < n and text[k + 1] not in ('if', '{'):
                out.append((0, 'header', k + 1))
            elif x in ('case', 'default') and k == 0:
                for m in range(k + 1, n):
                    if text[m] == ':' and toks[m - 1].end == toks[m].start:
                        if m + 1 < n:
                            out.append((0, 'header', m + 1))
                        break
                    if text[m] in ('(', '[', '{', '?'):
                        break
    keep = []
    for d, cls, b in out:
        if not 0 < b < n:
            continue
        # a break inside brackets that close before the limit is a last resort (a break in a later pair helps more)
        g = enclosing[b]
        close = matching(line, toks, g) if g is not None and cls != 'block' else None
        keep.append((d, cls, b, close is not None and p.width(0, close + 1) <= LIMIT))
    return keep


def split_at(p, breaks, step, nested=False):
    """Pieces of p broken before each index in breaks (nested: each one indented a step deeper than the last)."""
    cont = p.indent + ' ' * step
    pieces, a = [], 0
    for i, b in enumerate(breaks + [len(p.toks)]):
        if nested:
            cont = p.indent + ' ' * (step * i)
        before = tok_text(p.line, p.toks[a - 1]) if a > 0 else p.before
        after = tok_text(p.line, p.toks[b]) if b < len(p.toks) else p.after
        pieces.append(Piece(p.line, p.toks[a:b], p.indent if a == 0 else cont, before, after))
        a = b
    return pieces


def greedy(p, positions, step):
    cont = p.indent + ' ' * step
    breaks, a, indent = [], 0, p.indent
    positions = sorted(positions)
    while True:
        later = [b for b in positions if b > a]
        if not later or p.width(a, indent=indent) <= LIMIT:
            break
        fit = [b for b in later if p.width(a, b, indent) <= LIMIT]
        b = fit[-1] if fit else later[0]
        breaks.append(b)
        a, indent = b, cont
    return breaks


def wrap_piece(p, out, depth_guard=0):
    """Append the lines of piece p to out; returns False when a line of it stays too long."""
    if p.width() <= LIMIT:
        out.append(p.indent + p.text())
        return True
    cands = candidates(p)
    order = sorted({(d, early, CLASSES[c][0], c) for d, c, _, early in cands})
    for d, early, _, cls in order:
        _, step, fill = CLASSES[cls]
        positions = sorted(b for dd, c, b, e in cands if dd == d and c == cls and e == early)
        if cls == 'block':
            return wrap_block(p, positions[0] - 1, out, depth_guard)
        if cls == 'chain' and tok_text(p.line, p.toks[0]) in ('.', '?.'):
            step = 0  # a line of a chain: its next call lines up with it
        if cls in ('assign', 'open', 'arrow'):
            # only when what follows then fits on one line (and, for `=`, the statement ends there and has no chain)
            b = positions[0]
            if p.width(b, indent=p.indent + ' ' * step) > LIMIT:
                continue
            if cls == 'assign' and (tok_text(p.line, p.toks[-1]) not in (';', ',')
                                    or any(c == 'chain' and dd == d for dd, c, _, _ in cands)):
                continue
            positions = [b]
        breaks = greedy(p, positions, step) if fill else positions
        if not breaks:
            continue
        ok = True
        for q in split_at(p, breaks, step, cls == 'header'):
            ok &= wrap_piece(q, out, depth_guard)
        return ok
    if depth_guard < 4:
        line = split_string(p)
        if line is not None:
            toks = lex_lines(line)[0][1]
            return wrap_piece(Piece(line, toks, p.indent, p.before, p.after), out, depth_guard + 1)
    out.append(p.indent + p.text())
    return False


def wrap_block(p, k, out, depth_guard):
    """`head { a; b; } tail` as head, `{`, a statement a line, `} tail` (a statement's or a lambda's block)."""
    line, toks = p.line, p.toks
    m = matching(line, toks, k)
    ok = True
    if k > 0:
        ok &= wrap_piece(Piece(line, toks[:k], p.indent, p.before, '{'), out, depth_guard)
    out.append(p.indent + '{')
    inner = p.indent + ' ' * STEP
    depth, a = 0, k + 1
    for j in range(k + 1, m):
        x = tok_text(line, toks[j])
        if x in '([{':
            depth += 1
        elif x in ')]}':
            depth -= 1
        if depth == 0 and (x == ';' or (x == '}' and j + 1 < m and tok_text(line, toks[j + 1]) != ';')):
            ok &= wrap_piece(Piece(line, toks[a:j + 1], inner, '{', ''), out, depth_guard)
            a = j + 1
    if a < m:
        ok &= wrap_piece(Piece(line, toks[a:m], inner, '{', '}'), out, depth_guard)
    closing = p.indent + line[toks[m].start:toks[-1].end]
    out.append(closing)
    return ok and len(closing) <= LIMIT


def literal_parts(line, t):
    """(opening, content, closing, positions in content after which it may be split) of a splittable literal."""
    s = tok_text(line, t)
    if t.sub not in ('plain', 'interp'):
        return None
    opening = '$"' if t.sub == 'interp' else '"'
    if not s.startswith(opening) or not s.endswith('"') or len(s) < 2:
        return None
    content = s[len(opening):-1]
    base = t.start + len(opening)
    inside = set()
    for a, b in t.holes:
        inside.update(range(a - base, b - base))
    tag = False  # inside an HTML/XML tag of the text: a break there only when nothing else fits
    splits, fallback = [], []
    for i, ch in enumerate(content):
        if i in inside:
            continue
        if ch == '<' and (content[i + 1:i + 2].isalpha() or content[i + 1:i + 2] == '/'):
            if i > 0 and content[i - 1] == '>' and (i - 1) not in inside:
                splits.append(i)  # between two tags
            tag = True
        elif ch == '>':
            tag = False
        elif ch == ' ' and i + 1 < len(content) and content[i + 1] != ' ':
            (fallback if tag else splits).append(i + 1)
        elif ch == ',' and i + 1 < len(content) and content[i + 1] != ' ':
            fallback.append(i + 1)  # a CSV row
    return opening, content, '"', splits, fallback


def split_string(p):
    """The piece's line with the first literal that crosses the limit split into a concatenation, or None."""
    line, toks = p.line, p.toks
    for k, t in enumerate(toks):
        col = len(p.indent) + t.start - toks[0].start
        last = not any(u.kind == 'str' for u in toks[k + 1:])  # then what follows it stays on its line too
        if t.kind != 'str' or col + (p.width(k, indent='') if last else t.end - t.start) <= LIMIT:
            continue
        parts = literal_parts(line, t)
        if parts is None:
            return None
        before = tok_text(line, toks[k - 1]) if k > 0 else p.before
        after = tok_text(line, toks[k + 1]) if k + 1 < len(toks) else p.after
        if before not in SAFE_BEFORE or after not in SAFE_AFTER:
            return None
        opening, content, closing, splits, fallback = parts
        tail = len(p.text(k + 1)) if k + 1 < len(toks) else 0
        cont = len(p.indent) + STEP + 2  # `+ ` starts a continuation line
        chunks, a, room = [], 0, LIMIT - col - len(opening) - len(closing)
        while True:
            if len(content) - a + tail <= room:
                chunks.append(content[a:])
                break
            fit = [s for s in splits if a < s and s - a <= room] or [s for s in fallback if a < s and s - a <= room]
            later = [s for s in splits if a < s] or [s for s in fallback if a < s]
            if not later:
                chunks.append(content[a:])
                break
            s = fit[-1] if fit else later[0]
            cont_room = LIMIT - cont - len(opening) - len(closing)
            if len(content) - s + tail <= cont_room and len(content) - s < 30:
                # the rest would be a short last line: break earlier, where the rest still fits on one line
                even = [e for e in fit if 30 <= len(content) - e and len(content) - e + tail <= cont_room]
                s = even[-1] if even else s
            chunks.append(content[a:s])
            a, room = s, LIMIT - cont - len(opening) - len(closing)
        if len(chunks) < 2:
            return None
        literal = ' + '.join(opening + c + closing for c in chunks)
        new = line[toks[0].start:t.start] + literal + line[t.end:toks[-1].end]
        return p.indent + new
    return None


# ---------------------------------------------------------------------------------------------------------- comments

COMMENT = re.compile(r'^(\s*//+ *)(.*)$')
ATOM = re.compile(r'<[^<>\s][^<>]*>|`[^`]*`')
BLOCK_END = re.compile(r'</(summary|remarks|para|returns|param|typeparam|value|example|code|list|item|description|term|'
                       r'exception|listheader)>\s*$')


def comment_split(prefix, text, limit=LIMIT):
    """(first, rest) of a comment's text broken at the last space that keeps prefix + first within the limit."""
    atomic = set()
    for m in ATOM.finditer(text):
        atomic.update(range(m.start(), m.end()))
    spaces = [i for i, ch in enumerate(text) if ch == ' ' and i not in atomic and text[:i].strip() and text[i:].strip()]
    if not spaces:
        return None
    fit = [i for i in spaces if len(prefix) + len(text[:i].rstrip()) <= limit]
    i = fit[-1] if fit else spaces[0]
    return text[:i].rstrip(), text[i:].lstrip()


def mergeable(rest, next_text):
    if not next_text or BLOCK_END.search(rest) or rest.endswith(':'):
        return False
    if next_text[0] in '<-*•|+#' or re.match(r'\d+[.)] ', next_text) or next_text.startswith(('e.g.', '(', '{')):
        return next_text.startswith('(') and not next_text.startswith(('(1)', '(a)', '(i)'))
    return next_text[0].isalnum() or next_text[0] in '`"\'[≈∑∫Σπλ'


# ---------------------------------------------------------------------------------------------------------- files

def first_last(lines_tokens, lines, i, which):
    """The first token of the next code line (which = 1) or the last one of the previous (which = -1)."""
    j = i + which
    while 0 <= j < len(lines):
        toks = [t for t in lines_tokens[j][1] if t.kind not in ('comment', 'block')]
        if toks:
            t = toks[0] if which == 1 else toks[-1]
            return lines[j][t.start:t.end]
        j += which
    return ''


def wrap_text(src, path, failures):
    lines = src.split('\n')
    info = lex_lines(src)
    out = []
    pending = None  # (prefix, text) carried to the next line of the same comment
    i = 0
    while i < len(lines):
        if pending is not None:
            prefix, rest = pending
            pending = None
            m = COMMENT.match(lines[i]) if i < len(lines) else None
            clean, toks = info[i]
            if clean and len(toks) == 1 and toks[0].kind == 'comment' and m and m.group(1) == prefix \
                    and mergeable(rest, m.group(2)):
                lines[i] = prefix + rest + ' ' + m.group(2)
            else:
                lines.insert(i, prefix + rest)
                info.insert(i, None)
            info[i] = [True, [Token('comment', prefix.index('/'), len(lines[i]))]]
        line, (clean, toks) = lines[i], info[i]
        if len(line) <= LIMIT:
            out.append(line)
            i += 1
            continue
        where = f'{path}:{len(out) + 1}'  # the line's number in the rewritten file
        if not clean or not toks or any(t.kind in ('pp', 'block') for t in toks):
            failures.append(where)
            out.append(line)
            i += 1
            continue
        indent = line[:len(line) - len(line.lstrip())]
        mark = len(out)
        if toks[-1].kind == 'comment':
            comment = line[toks[-1].start:]
            if len(toks) == 1:
                m = COMMENT.match(line)
                split = comment_split(m.group(1), m.group(2))
                if split is None:
                    failures.append(where)
                    out.append(line)
                else:
                    out.append(m.group(1) + split[0])
                    pending = (m.group(1), split[1])
                i += 1
                continue
            # a trailing comment goes above the code
            m = COMMENT.match(indent + comment)
            c = indent + comment
            while len(c) > LIMIT:
                split = comment_split(m.group(1), c[len(m.group(1)):])
                if split is None:
                    failures.append(where)
                    break
                out.append(m.group(1) + split[0])
                c = m.group(1) + split[1]
            out.append(c)
            toks = toks[:-1]
        new = []
        piece = Piece(line, toks, indent, first_last(info, lines, i, -1), first_last(info, lines, i, 1))
        if wrap_piece(piece, new):
            out.extend(new)
        else:
            del out[mark:]
            failures.append(f'{path}:{len(out) + 1}')
            out.append(line)
        i += 1
    if pending is not None:
        out.append(pending[0] + pending[1])
    return '\n'.join(out)


def source_files(roots, repo):
    corpus = os.path.join(repo, 'tests', 'corpus') + os.sep
    for root in roots:
        if os.path.isfile(root):
            yield root
            continue
        for d, dirs, files in os.walk(root):
            dirs[:] = sorted(x for x in dirs if x not in ('bin', 'obj', 'node_modules')
                             and not (os.path.join(d, x) + os.sep).startswith(corpus))
            for f in sorted(files):
                if f.endswith('.cs'):
                    yield os.path.join(d, f)


def main(argv):
    global LIMIT
    check = '--check' in argv
    args = [a for a in argv if a != '--check']
    if '--limit' in args:
        k = args.index('--limit')
        LIMIT = int(args[k + 1])
        del args[k:k + 2]
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    roots = args or [os.path.join(repo, 'src'), os.path.join(repo, 'tests')]
    failures, changed = [], []
    for f in source_files(roots, repo):
        with open(f, encoding='utf-8', newline='') as h:
            src = h.read()
        new = wrap_text(src, os.path.relpath(f), failures)
        if new != src:
            changed.append(f)
            if not check:
                with open(f, 'w', encoding='utf-8', newline='') as h:
                    h.write(new)
    for f in failures:
        print(f'{f}: cannot be wrapped safely; wrap it by hand', file=sys.stderr)
    verb = 'would change' if check else 'changed'
    print(f'wrap-lines: {len(changed)} files {verb}, {len(failures)} lines left too long (limit {LIMIT})')
    if failures:
        return 2
    return 1 if check and changed else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
