"""A parser of the OMG IDL subset that wbi's message types use (idl/*.idl).

    types = parse_idl(text)                    # {"wbi::msg::Header": Struct, ...}
    state = resolve(types, "wbi::msg::StateEstimate")

Understood: modules (nested), structs (with single inheritance), enums,
typedefs, integer constants (used as bounds), sequences (bounded or not),
arrays (any number of dimensions), strings (bounded or not), the primitive
types, scoped names; comments, preprocessor lines and @annotations are
skipped. Unions, bitsets and value types are not (an error names them).
"""

import re
from dataclasses import dataclass, field

__all__ = ["IdlError", "Primitive", "String", "Sequence", "Array", "Enum", "Struct",
           "parse_idl", "resolve"]


class IdlError(Exception):
    """The IDL text is not in the understood subset; the message names the line."""


@dataclass(frozen=True)
class Primitive:
    name: str  # IDL spelling, e.g. "double", "uint16"
    code: str  # struct module format character
    size: int


@dataclass(frozen=True)
class String:
    bound: int = 0  # 0: unbounded


@dataclass(frozen=True)
class Sequence:
    element: object
    bound: int = 0


@dataclass(frozen=True)
class Array:
    element: object
    dims: tuple


@dataclass
class Enum:
    name: str
    enumerators: dict = field(default_factory=dict)  # value -> name


@dataclass
class Struct:
    name: str
    members: list = field(default_factory=list)  # [(name, type)]


_PRIMITIVES = {
    "boolean": ("?", 1), "bool": ("?", 1), "octet": ("B", 1), "char": ("c", 1),
    "int8": ("b", 1), "uint8": ("B", 1), "int16": ("h", 2), "uint16": ("H", 2),
    "int32": ("i", 4), "uint32": ("I", 4), "int64": ("q", 8), "uint64": ("Q", 8),
    "short": ("h", 2), "unsigned short": ("H", 2), "long": ("i", 4), "unsigned long": ("I", 4),
    "long long": ("q", 8), "unsigned long long": ("Q", 8), "float": ("f", 4),
    "double": ("d", 8), "float32": ("f", 4), "float64": ("d", 8),
}

_TOKEN = re.compile(r"\s*(?:(?P<name>[A-Za-z_][A-Za-z0-9_]*(?:::[A-Za-z_][A-Za-z0-9_]*)*)"
                    r"|(?P<number>0[xX][0-9a-fA-F]+|\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)"
                    r"|(?P<string>\"(?:[^\"\\]|\\.)*\")"
                    r"|(?P<scope>::)"
                    r"|(?P<punct>[{}<>;,\[\]=()@:+\-*/]))")


def _strip(text):
    """Removes comments and preprocessor lines, keeping line numbers."""
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    return "\n".join("" if line.lstrip().startswith("#") else line for line in text.split("\n"))


def _tokenize(text):
    tokens = []
    for number, line in enumerate(_strip(text).split("\n"), start=1):
        at = 0
        while at < len(line):
            if line[at:].strip() == "":
                break
            match = _TOKEN.match(line, at)
            if not match:
                raise IdlError(f"line {number}: unexpected character {line[at:].strip()[0]!r}")
            kind = match.lastgroup
            tokens.append((kind, match.group(kind), number))
            at = match.end()
    return tokens


class _Parser:
    def __init__(self, text):
        self.tokens = _tokenize(text)
        self.at = 0
        self.types = {}  # qualified name -> type
        self.constants = {}  # qualified name -> value

    # ---- tokens ----
    def peek(self, offset=0):
        index = self.at + offset
        return self.tokens[index][1] if index < len(self.tokens) else None

    def line(self):
        token = self.tokens[min(self.at, len(self.tokens) - 1)] if self.tokens else None
        return token[2] if token else 0

    def next(self):
        if self.at >= len(self.tokens):
            raise IdlError("unexpected end of the IDL text")
        token = self.tokens[self.at]
        self.at += 1
        return token[1]

    def expect(self, value):
        got = self.next()
        if got != value:
            raise IdlError(f"line {self.tokens[self.at - 1][2]}: expected '{value}', found '{got}'")

    def name(self):
        kind, value, line = self.tokens[self.at] if self.at < len(self.tokens) else (None, None, 0)
        if kind != "name":
            raise IdlError(f"line {line}: expected a name, found '{value}'")
        self.at += 1
        return value

    # ---- scopes ----
    def lookup(self, name, scope, table):
        if name.startswith("::"):
            name = name[2:]
        for depth in range(len(scope), -1, -1):
            qualified = "::".join(scope[:depth] + [name])
            if qualified in table:
                return table[qualified]
        return None

    # ---- grammar ----
    def definitions(self, scope, until=None):
        while self.at < len(self.tokens) and self.peek() != until:
            self.annotations()
            keyword = self.peek()
            if keyword == ";":
                self.next()
            elif keyword == "module":
                self.next()
                name = self.name()
                self.expect("{")
                self.definitions(scope + [name], until="}")
                self.expect("}")
            elif keyword == "struct":
                self.struct(scope)
            elif keyword == "enum":
                self.enum(scope)
            elif keyword == "typedef":
                self.next()
                base = self.type_spec(scope)
                name, dims = self.declarator(scope)
                self.types["::".join(scope + [name])] = Array(base, dims) if dims else base
            elif keyword == "const":
                self.next()
                self.type_spec(scope)
                name = self.name()
                self.expect("=")
                self.constants["::".join(scope + [name])] = self.expression(scope, allow_text=True)
            else:
                raise IdlError(f"line {self.line()}: '{keyword}' is not supported "
                               "(modules, structs, enums, typedefs and constants are)")

    def annotations(self):
        while self.peek() == "@":
            self.next()
            self.name()
            if self.peek() == "(":
                depth = 0
                while True:
                    token = self.next()
                    depth += token == "("
                    depth -= token == ")"
                    if depth == 0:
                        break

    def struct(self, scope):
        self.next()
        name = self.name()
        qualified = "::".join(scope + [name])
        if self.peek() == ";":  # forward declaration
            self.types.setdefault(qualified, Struct(qualified))
            return
        struct = self.types.get(qualified)
        if not isinstance(struct, Struct):
            struct = Struct(qualified)
            self.types[qualified] = struct
        if self.peek() == ":":
            self.next()
            base = self.resolve_name(self.name(), scope)
            struct.members.extend(base.members)
        self.expect("{")
        while self.peek() != "}":
            self.annotations()
            member_type = self.type_spec(scope)
            while True:
                self.annotations()
                member, dims = self.declarator(scope)
                struct.members.append((member, Array(member_type, dims) if dims else member_type))
                if self.peek() != ",":
                    break
                self.next()
            self.expect(";")
        self.expect("}")

    def enum(self, scope):
        self.next()
        name = self.name()
        enum = Enum("::".join(scope + [name]))
        self.types[enum.name] = enum
        self.expect("{")
        value = 0
        while self.peek() != "}":
            self.annotations()
            enumerator = self.name()
            if self.peek() == "=":
                self.next()
                value = self.expression(scope)
            enum.enumerators[value] = enumerator
            self.constants["::".join(scope + [enumerator])] = value
            value += 1
            if self.peek() == ",":
                self.next()
        self.expect("}")

    def declarator(self, scope):
        name = self.name()
        dims = []
        while self.peek() == "[":
            self.next()
            dims.append(self.expression(scope))
            self.expect("]")
        return name, tuple(dims)

    def expression(self, scope, allow_text=False):
        """An integer literal or constant, optionally combined with + - * /."""
        value = self.term(scope, allow_text)
        while self.peek() in ("+", "-", "*", "/"):
            operator = self.next()
            right = self.term(scope, allow_text)
            value = {"+": value + right, "-": value - right, "*": value * right,
                     "/": value // right if isinstance(value, int) else value / right}[operator]
        return value

    def term(self, scope, allow_text):
        kind, value, line = self.tokens[self.at]
        self.at += 1
        if value == "-":
            return -self.term(scope, allow_text)
        if value == "(":
            result = self.expression(scope, allow_text)
            self.expect(")")
            return result
        if kind == "number":
            return int(value, 0) if re.fullmatch(r"0[xX][0-9a-fA-F]+|\d+", value) else float(value)
        if kind == "string" and allow_text:
            return value[1:-1]
        if kind == "name":
            if value in ("TRUE", "FALSE"):
                return value == "TRUE"
            constant = self.lookup(value, scope, self.constants)
            if constant is None:
                raise IdlError(f"line {line}: unknown constant '{value}'")
            return constant
        raise IdlError(f"line {line}: expected a constant expression, found '{value}'")

    def type_spec(self, scope):
        word = self.name()
        if word == "unsigned":
            word += " " + self.name()
            if word == "unsigned long" and self.peek() == "long":
                word += " " + self.name()
        elif word == "long" and self.peek() == "long":
            word += " " + self.name()
        elif word == "long" and self.peek() == "double":
            raise IdlError(f"line {self.line()}: long double is not supported")
        if word in _PRIMITIVES:
            code, size = _PRIMITIVES[word]
            return Primitive(word, code, size)
        if word in ("string", "wstring"):
            if word == "wstring":
                raise IdlError(f"line {self.line()}: wstring is not supported")
            bound = 0
            if self.peek() == "<":
                self.next()
                bound = self.expression(scope)
                self.expect(">")
            return String(bound)
        if word == "sequence":
            self.expect("<")
            element = self.type_spec(scope)
            bound = 0
            if self.peek() == ",":
                self.next()
                bound = self.expression(scope)
            self.expect(">")
            return Sequence(element, bound)
        if word in ("union", "bitset", "bitmask", "map", "any", "fixed", "valuetype"):
            raise IdlError(f"line {self.line()}: '{word}' is not supported")
        return self.resolve_name(word, scope)

    def resolve_name(self, name, scope):
        found = self.lookup(name, scope, self.types)
        if found is None:
            raise IdlError(f"line {self.line()}: unknown type '{name}'")
        return found


def parse_idl(text):
    """{qualified name: type} of every struct, enum and typedef of an IDL text."""
    parser = _Parser(text)
    parser.definitions([])
    return parser.types


def resolve(types, name):
    """The type called `name` ("wbi::msg::X", "wbi/msg/X", or a unique short name)."""
    qualified = name.replace("/", "::").lstrip(":")
    if qualified in types:
        return types[qualified]
    matches = [key for key in types if key.endswith("::" + qualified)]
    if len(matches) == 1:
        return types[matches[0]]
    raise IdlError(f"the schema does not define type '{name}'"
                   + (f" (ambiguous: {', '.join(matches)})" if matches else ""))
