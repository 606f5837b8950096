"""The landscape formula language of FORMATS.md, evaluated with NumPy.

A small recursive-descent parser builds a tree of tuples; evaluation runs
the tree as a postfix program of NumPy functions, so a formula can be evaluated on a whole grid at
once. Nothing is ever passed to eval() or exec(): a formula can only name
x, y, pi, e, the scene's params and the listed functions. The grammar and the
messages follow problems/formula.cpp so that the plots accept exactly the
formulas the C++ code accepts.
"""
import math
import sys

import numpy as np

MAX_LENGTH = 65536
# keeps the recursion far from Python's own limit, like the C++ parser's
MAX_DEPTH = 200

FUNCTIONS = {
    "sin": (np.sin, 1), "cos": (np.cos, 1), "tan": (np.tan, 1),
    "asin": (np.arcsin, 1), "acos": (np.arccos, 1), "atan": (np.arctan, 1),
    "sinh": (np.sinh, 1), "cosh": (np.cosh, 1), "tanh": (np.tanh, 1),
    "exp": (np.exp, 1), "log": (np.log, 1), "sqrt": (np.sqrt, 1),
    "atan2": (np.arctan2, 2), "hypot": (np.hypot, 2),
}

# the equations of motion need f in C^2; each with a smooth stand-in
_STAIRCASE = "use x - sin(2*pi*x)/(2*pi) for a smooth staircase"
NON_SMOOTH = {
    "abs": "use sqrt(x^2 + eps) for a smooth stand-in",
    "min": "use (a + b - sqrt((a - b)^2 + eps))/2 for a smooth stand-in",
    "max": "use (a + b + sqrt((a - b)^2 + eps))/2 for a smooth stand-in",
    "sign": "use tanh(x/eps) for a smooth stand-in",
    "floor": _STAIRCASE, "ceil": _STAIRCASE, "round": _STAIRCASE,
}
CONSTANTS = {"pi": math.pi, "e": math.e}
BINARY = {"+": np.add, "-": np.subtract, "*": np.multiply, "/": np.divide, "^": np.power}


class FormulaError(ValueError):
    """A formula that does not parse; column is 1-based (0: no place in the text)."""

    def __init__(self, message, column=0):
        super().__init__(f"column {column}: {message}" if column else message)
        self.message = message
        self.column = column


def _quoted(s):
    return f"'{s}'" if len(s) <= 32 else f"'{s[:32]}...'"


def _tokens(text):
    """(kind, spelling, position) triples; kind is num, name, an operator, or end."""
    i, n = 0, len(text)
    while True:
        while i < n and text[i] in " \t\r\n":
            i += 1
        if i == n:
            yield ("end", "", i)
            return
        c = text[i]
        if c.isascii() and (c.isdigit() or (c == "." and i + 1 < n and text[i + 1].isdigit())):
            j = i
            while j < n and text[j].isdigit():
                j += 1
            if j < n and text[j] == ".":
                j += 1
                while j < n and text[j].isdigit():
                    j += 1
            bad = False
            if j < n and text[j] in "eE":
                k = j + 1
                if k < n and text[k] in "+-":
                    k += 1
                if k < n and text[k].isdigit():
                    j = k
                    while j < n and text[j].isdigit():
                        j += 1
                else:
                    bad = True
            if bad or (j < n and (text[j].isalnum() or text[j] in "_.")):
                k = i
                while k < n and (text[k].isalnum() or text[k] in "_." or
                                 (text[k] in "+-" and text[k - 1] in "eE")):
                    k += 1
                raise FormulaError(f"malformed number {_quoted(text[i:k])}", i + 1)
            value = float(text[i:j])
            if not math.isfinite(value):
                raise FormulaError(f"number {_quoted(text[i:j])} is out of range for a double", i + 1)
            yield ("num", text[i:j], i)
            i = j
        elif c.isascii() and (c.isalpha() or c == "_"):
            j = i
            while j < n and text[j].isascii() and (text[j].isalnum() or text[j] == "_"):
                j += 1
            yield ("name", text[i:j], i)
            i = j
        elif text.startswith("**", i):
            yield ("^", "**", i)
            i += 2
        elif c in "+-*/^(),":
            yield (c, c, i)
            i += 1
        elif c.isascii() and c.isprintable():
            raise FormulaError(f"unexpected character '{c}'", i + 1)
        elif not c.isascii():
            raise FormulaError("unexpected non-ASCII character; formulas are plain ASCII", i + 1)
        else:
            raise FormulaError(f"unexpected control character (byte 0x{ord(c):02X})", i + 1)


class _Parser:
    def __init__(self, text, params):
        self.text = text
        self.params = params
        self.toks = _tokens(text)
        self.prev = None
        self.tok = next(self.toks)
        self.depth = 0

    def advance(self):
        self.prev, self.tok = self.tok, next(self.toks)

    def fail(self, message, tok):
        raise FormulaError(message, tok[2] + 1)

    def describe(self, tok):
        return "the end of the formula" if tok[0] == "end" else _quoted(tok[1])

    def nest(self, tok):
        self.depth += 1
        if self.depth > MAX_DEPTH:
            self.fail(f"formula nests deeper than {MAX_DEPTH} levels", tok)

    def parse(self):
        tree = self.sum()
        if self.tok[0] == ")":
            self.fail("')' has no matching '('", self.tok)
        if self.tok[0] == ",":
            self.fail("',' outside a function's argument list", self.tok)
        if self.tok[0] != "end":
            self.fail("expected an operator before " + self.describe(self.tok), self.tok)
        return tree

    # sum := product (('+' | '-') product)*
    def sum(self):
        left = self.product()
        while self.tok[0] in ("+", "-"):
            op = self.tok[0]
            self.advance()
            left = ("bin", op, left, self.product())
        return left

    # product := unary (('*' | '/') unary)*
    def product(self):
        left = self.unary()
        while self.tok[0] in ("*", "/"):
            op = self.tok[0]
            self.advance()
            left = ("bin", op, left, self.unary())
        return left

    # unary := ('-' | '+') unary | power; so -x^2 = -(x^2)
    def unary(self):
        if self.tok[0] not in ("+", "-"):
            return self.power()
        minus = self.tok[0] == "-"
        self.nest(self.tok)
        self.advance()
        u = self.unary()
        self.depth -= 1
        return ("neg", u) if minus else u

    # power := primary (('^' | '**') unary)?: right-associative, 2^-x allowed
    def power(self):
        base = self.primary()
        if self.tok[0] != "^":
            return base
        self.nest(self.tok)
        self.advance()
        exponent = self.unary()
        self.depth -= 1
        return ("bin", "^", base, exponent)

    def primary(self):
        kind = self.tok[0]
        if kind == "num":
            value = float(self.tok[1])
            self.advance()
            return ("num", value)
        if kind == "(":
            open_tok = self.tok
            self.nest(open_tok)
            self.advance()
            inner = self.sum()
            if self.tok[0] == ")":
                self.advance()
                self.depth -= 1
                return inner
            if self.tok[0] == "end":
                self.fail("missing ')' to close this '('", open_tok)
            if self.tok[0] == ",":
                self.fail("',' outside a function's argument list", self.tok)
            self.fail("expected an operator or ')' before " + self.describe(self.tok), self.tok)
        if kind == "name":
            return self.name()
        if self.prev is None:
            self.fail("expected an operand, found " + self.describe(self.tok), self.tok)
        self.fail("expected an operand after " + self.describe(self.prev), self.tok)

    def name(self):
        name_tok = self.tok
        name = name_tok[1]
        self.advance()
        call = self.tok[0] == "("
        if name in NON_SMOOTH:
            self.fail(f"{name} is not smooth: the landscape needs continuous second derivatives "
                      f"(MODEL.md); {NON_SMOOTH[name]}", name_tok)
        if name in FUNCTIONS:
            if not call:
                self.fail(f"{name} is a function: write {name}(...)", name_tok)
            return self.call(name, name_tok)
        known = name in ("x", "y") or name in CONSTANTS or name in self.params
        if call and known:
            self.fail(f"{_quoted(name)} is not a function; write {name}*(...) for a product", name_tok)
        if name in ("x", "y"):
            return ("var", name)
        if name in CONSTANTS:
            return ("num", CONSTANTS[name])
        if name in self.params:
            return ("num", self.params[name])
        message = ("unknown function " if call else "unknown name ") + _quoted(name)
        lower = name.lower()
        if lower != name and (lower in FUNCTIONS or lower in ("x", "y") or lower in CONSTANTS):
            message += f"; names are case-sensitive: did you mean '{lower}'?"
        elif call:
            message += "; the functions are " + " ".join(FUNCTIONS)
        else:
            listed = ", ".join(sorted(self.params)) if self.params else ""
            message += "; a formula knows x, y, pi, e" + (
                " and the params " + listed if listed else " and no params")
        self.fail(message, name_tok)

    # name '(' [sum (',' sum)*] ')'
    def call(self, name, name_tok):
        open_tok = self.tok
        self.nest(open_tok)
        self.advance()
        args = []
        if self.tok[0] == ")":
            self.advance()
        else:
            while True:
                args.append(self.sum())
                if self.tok[0] == ",":
                    self.advance()
                    continue
                if self.tok[0] == ")":
                    self.advance()
                    break
                if self.tok[0] == "end":
                    self.fail("missing ')' to close this '('", open_tok)
                self.fail("expected an operator, ',' or ')' before " + self.describe(self.tok), self.tok)
        self.depth -= 1
        arity = FUNCTIONS[name][1]
        if len(args) != arity:
            noun = "argument" if arity == 1 else "arguments"
            self.fail(f"{name} takes {arity} {noun}, got {len(args)}", name_tok)
        return ("call", name, args)


def parse(text, params=None):
    """The tree of a formula; raises FormulaError naming what and where."""
    if not isinstance(text, str):
        raise FormulaError("a formula is a string")
    if len(text) > MAX_LENGTH:
        raise FormulaError(f"formula is longer than {MAX_LENGTH} characters")
    params = dict(params or {})
    for key, value in params.items():
        if not (isinstance(key, str) and key.isascii() and key.isidentifier()):
            raise FormulaError(f"param name {_quoted(str(key))} is not a name")
        if key in ("x", "y") or key in CONSTANTS or key in FUNCTIONS or key in NON_SMOOTH:
            raise FormulaError(f"param {_quoted(key)} hides a built-in name")
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise FormulaError(f"param {_quoted(key)} must be a finite number")
        params[key] = float(value)
    # each nesting level costs about six Python frames; room for MAX_DEPTH levels
    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(max(limit, 8 * MAX_DEPTH + 500))
    try:
        return _Parser(text, params).parse()
    finally:
        sys.setrecursionlimit(limit)


def postfix(tree):
    """The tree as a postfix program; built without recursion, because a long
    sum (x + x + ... + x) makes a tree as deep as it is long."""
    program, stack = [], [(tree, False)]
    while stack:
        node, children_done = stack.pop()
        if children_done or node[0] in ("num", "var"):
            program.append(node)
            continue
        stack.append((node, True))
        children = [node[1]] if node[0] == "neg" else [node[2], node[3]] if node[0] == "bin" else node[2]
        stack.extend((child, False) for child in reversed(children))
    return program


def evaluate(tree, x, y):
    """f(x, y) elementwise; outside the formula's domain the result is NaN or inf."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    values = []
    with np.errstate(all="ignore"):
        for node in postfix(tree):
            kind = node[0]
            if kind == "num":
                values.append(node[1])
            elif kind == "var":
                values.append(x if node[1] == "x" else y)
            elif kind == "neg":
                values.append(np.negative(values.pop()))
            elif kind == "bin":
                b, a = values.pop(), values.pop()
                values.append(BINARY[node[1]](a, b))
            else:
                n = len(node[2])
                args, values[-n:] = values[-n:], []
                values.append(FUNCTIONS[node[1]][0](*args))
    return np.asarray(values[0], dtype=float)


class Landscape:
    """z = f(x, y) from a formula and its params, callable on arrays."""

    def __init__(self, text, params=None):
        self.text = text
        self.tree = parse(text, params)

    def __call__(self, x, y):
        z = evaluate(self.tree, x, y)
        return np.broadcast_to(z, np.broadcast(np.asarray(x), np.asarray(y)).shape).copy()
