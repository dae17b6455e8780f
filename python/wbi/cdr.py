"""Decoding CDR-encoded samples (what Fast DDS puts on the wire) with a type
from wbi.omgidl.

    decode = CdrDecoder(struct_type)
    value = decode(payload)   # dict of members; sequences/arrays of numbers as numpy arrays

The payload starts with the 4-byte encapsulation header: plain CDR (XCDR1,
Fast DDS's default) big or little endian, or plain CDR2 (XCDR2 final types,
where 8-byte values align to 4). Alignment counts from after the header.
Enums decode to their integer value, strings to str, booleans to bool.
"""

import struct

import numpy as np

from .omgidl import Array, Enum, Primitive, Sequence, String, Struct

__all__ = ["CdrError", "CdrDecoder"]

# encapsulation kind (second byte) -> (byte order, largest alignment)
_ENCAPSULATIONS = {0x00: (">", 8), 0x01: ("<", 8), 0x06: (">", 4), 0x07: ("<", 4)}
_ORIGIN = 4  # alignment origin: the first byte after the encapsulation header


class CdrError(Exception):
    """A sample that does not decode with its type; the message says where."""


def _align(position, size, max_align):
    size = min(size, max_align)
    return position + (-(position - _ORIGIN)) % size


def _compile(kind, order, max_align):
    """A function (buffer, position) -> (value, position) decoding `kind`."""
    if isinstance(kind, Primitive):
        return _primitive(kind, order, max_align)
    if isinstance(kind, Enum):
        return _primitive(Primitive("uint32", "I", 4), order, max_align)
    if isinstance(kind, String):
        return _string(order, max_align)
    if isinstance(kind, Sequence):
        return _sequence(kind, order, max_align)
    if isinstance(kind, Array):
        return _array(kind, order, max_align)
    if isinstance(kind, Struct):
        members = [(name, _compile(member, order, max_align)) for name, member in kind.members]

        def read_struct(buffer, position):
            value = {}
            for name, read in members:
                value[name], position = read(buffer, position)
            return value, position
        return read_struct
    raise CdrError(f"cannot decode IDL type {kind!r}")


def _primitive(kind, order, max_align):
    unpack = struct.Struct(order + kind.code).unpack_from
    size = kind.size
    char = kind.code == "c"

    def read(buffer, position):
        position = _align(position, size, max_align)
        value = unpack(buffer, position)[0]
        return (value.decode("latin-1") if char else value), position + size
    return read


def _string(order, max_align):
    length = struct.Struct(order + "I").unpack_from

    def read(buffer, position):
        position = _align(position, 4, max_align)
        size = length(buffer, position)[0]
        position += 4
        if position + size > len(buffer):
            raise struct.error("string runs past the end")
        text = bytes(buffer[position:position + size]).rstrip(b"\0").decode("utf-8", "replace")
        return text, position + size
    return read


def _numbers(element, order, max_align):
    """(dtype, size) when the element is a number (read in bulk with numpy), else None."""
    if isinstance(element, Enum):
        element = Primitive("uint32", "I", 4)
    if isinstance(element, Primitive) and element.code != "c":
        return np.dtype(order + element.code), element.size
    return None


def _bulk(dtype, size, max_align):
    def read(buffer, position, count):
        if count:
            position = _align(position, size, max_align)
        end = position + count * size
        if end > len(buffer):
            raise struct.error("array runs past the end")
        return np.frombuffer(buffer, dtype=dtype, count=count, offset=position), end
    return read


def _sequence(kind, order, max_align):
    length = struct.Struct(order + "I").unpack_from
    numbers = _numbers(kind.element, order, max_align)
    bulk = _bulk(*numbers, max_align) if numbers else None
    element = None if numbers else _compile(kind.element, order, max_align)

    def read(buffer, position):
        position = _align(position, 4, max_align)
        count = length(buffer, position)[0]
        position += 4
        if bulk:
            return bulk(buffer, position, count)
        values = []
        for _ in range(count):
            value, position = element(buffer, position)
            values.append(value)
        return values, position
    return read


def _array(kind, order, max_align):
    count = int(np.prod(kind.dims))
    numbers = _numbers(kind.element, order, max_align)
    if numbers:
        bulk = _bulk(*numbers, max_align)

        def read_numbers(buffer, position):
            values, position = bulk(buffer, position, count)
            return values.reshape(kind.dims), position
        return read_numbers
    element = _compile(kind.element, order, max_align)

    def read(buffer, position):
        values = []
        for _ in range(count):
            value, position = element(buffer, position)
            values.append(value)
        return values, position
    return read


class CdrDecoder:
    """Decodes serialized samples of one IDL type."""

    def __init__(self, kind, name=None):
        self.kind = kind
        self.name = name or getattr(kind, "name", repr(kind))
        self._readers = {}

    def __call__(self, payload):
        if len(payload) < 4:
            raise CdrError(f"{self.name}: {len(payload)} bytes, shorter than the CDR header")
        encapsulation = _ENCAPSULATIONS.get(payload[1]) if payload[0] == 0 else None
        if encapsulation is None:
            raise CdrError(f"{self.name}: encapsulation 0x{payload[0]:02x}{payload[1]:02x} is not "
                           "plain CDR or CDR2 (mutable/appendable XCDR2 types are not supported)")
        read = self._readers.get(encapsulation)
        if read is None:
            read = self._readers[encapsulation] = _compile(self.kind, *encapsulation)
        try:
            value, _ = read(payload, _ORIGIN)
        except struct.error:
            raise CdrError(f"{self.name}: sample of {len(payload)} bytes is too short for its "
                           "type") from None
        return value
