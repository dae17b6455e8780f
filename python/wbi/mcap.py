"""A pure-Python reader of MCAP files (https://mcap.dev/spec, format version 0).

    reader = McapReader("run.mcap")
    reader.schemas, reader.channels           # {id: Schema}, {id: Channel}
    for message in reader.messages():          # log-time order (file order for ties)
        message.channel.topic, message.log_time, message.data

The data section is scanned record by record (the summary is not needed, so a
file cut short by a killed recorder reads up to its last complete record and
`truncated` / `warnings` say so). Chunks: uncompressed always; zstd through
python3-zstandard or else the system's libzstd.so.1 (ctypes); lz4 through
python3-lz4. A missing decompressor is an error naming the Debian package.
Corrupt files raise McapError naming the file and the byte offset.
"""

import ctypes
import ctypes.util
import struct
import zlib
from dataclasses import dataclass, field

__all__ = ["McapError", "McapReader", "Schema", "Channel", "Message"]

MAGIC = b"\x89MCAP0\r\n"

OP_FOOTER, OP_SCHEMA, OP_CHANNEL, OP_MESSAGE, OP_CHUNK = 0x02, 0x03, 0x04, 0x05, 0x06
OP_DATA_END = 0x0F


class McapError(Exception):
    """A corrupt or unreadable MCAP file; the message names the file and the byte offset."""


@dataclass
class Schema:
    id: int
    name: str
    encoding: str
    data: bytes


@dataclass
class Channel:
    id: int
    schema_id: int
    topic: str
    message_encoding: str
    metadata: dict = field(default_factory=dict)


@dataclass
class Message:
    channel: Channel
    sequence: int
    log_time: int  # ns
    publish_time: int  # ns
    data: bytes


class _Fields:
    """Reads the fields of one record's content, checking every length."""

    def __init__(self, buffer, start, end, where):
        self.buffer, self.at, self.end, self.where = buffer, start, end, where

    def _take(self, size, what):
        if self.at + size > self.end:
            raise McapError(f"{self.where}: {what} overruns its record")
        start = self.at
        self.at += size
        return start

    def u16(self, what):
        return struct.unpack_from("<H", self.buffer, self._take(2, what))[0]

    def u32(self, what):
        return struct.unpack_from("<I", self.buffer, self._take(4, what))[0]

    def u64(self, what):
        return struct.unpack_from("<Q", self.buffer, self._take(8, what))[0]

    def bytes_u32(self, what):
        size = self.u32(what)
        start = self._take(size, what)
        return bytes(self.buffer[start:start + size])

    def string(self, what):
        return self.bytes_u32(what).decode("utf-8", errors="replace")

    def string_map(self, what):
        size = self.u32(what)
        end = self.at + size
        if end > self.end:
            raise McapError(f"{self.where}: {what} overruns its record")
        result = {}
        while self.at < end:
            key = self.string(what)
            result[key] = self.string(what)
        return result

    def rest(self):
        start, self.at = self.at, self.end
        return self.buffer[start:self.end]


_libzstd = None


def _zstd_decompress(data, size):
    try:
        import zstandard  # python3-zstandard
        return zstandard.ZstdDecompressor().decompress(data, max_output_size=size)
    except ImportError:
        pass
    global _libzstd
    if _libzstd is None:
        name = ctypes.util.find_library("zstd") or "libzstd.so.1"
        try:
            _libzstd = ctypes.CDLL(name)
        except OSError:
            raise McapError("chunks compressed with zstd need python3-zstandard "
                            "(apt install python3-zstandard) or libzstd1") from None
        _libzstd.ZSTD_decompress.restype = ctypes.c_size_t
        _libzstd.ZSTD_decompress.argtypes = [ctypes.c_void_p, ctypes.c_size_t, ctypes.c_char_p,
                                             ctypes.c_size_t]
        _libzstd.ZSTD_isError.restype = ctypes.c_uint
        _libzstd.ZSTD_isError.argtypes = [ctypes.c_size_t]
    out = ctypes.create_string_buffer(max(size, 1))
    written = _libzstd.ZSTD_decompress(out, size, bytes(data), len(data))
    if _libzstd.ZSTD_isError(written):
        raise ValueError("zstd: corrupt data")
    return out.raw[:written]


def _lz4_decompress(data, size):
    try:
        import lz4.frame  # python3-lz4
    except ImportError:
        raise McapError("chunks compressed with lz4 need python3-lz4 (apt install python3-lz4)") \
            from None
    return lz4.frame.decompress(bytes(data))


_DECOMPRESSORS = {"zstd": _zstd_decompress, "lz4": _lz4_decompress}


class McapReader:
    """Schemas, channels and messages of one MCAP file (read at construction)."""

    def __init__(self, path):
        self.path = str(path)
        self.schemas = {}
        self.channels = {}
        self.truncated = False
        self.warnings = []
        self._messages = []  # (log_time, order, Message)
        try:
            with open(self.path, "rb") as file:
                self._buffer = memoryview(file.read())
        except OSError as error:
            raise McapError(f"{self.path}: {error.strerror}") from None
        if bytes(self._buffer[:len(MAGIC)]) != MAGIC:
            raise McapError(f"{self.path}: byte 0: not an MCAP file (bad magic)")
        self._scan(self._buffer, len(MAGIC), len(self._buffer), top_level=True)

    def messages(self, topics=None):
        """Messages in log-time order (file order for equal times); topics: only these."""
        wanted = None if topics is None else set([topics] if isinstance(topics, str) else topics)
        for _, _, message in sorted(self._messages, key=lambda m: (m[0], m[1])):
            if wanted is None or message.channel.topic in wanted:
                yield message

    @property
    def topics(self):
        return sorted({channel.topic for channel in self.channels.values()})

    def _scan(self, buffer, at, end, top_level, chunk_offset=None):
        while at < end:
            where = (f"{self.path}: byte {at}" if chunk_offset is None
                     else f"{self.path}: chunk at byte {chunk_offset}, record at {at}")
            if at + 9 > end:
                self._cut(where, "record header", top_level)
                return
            opcode = buffer[at]
            length = struct.unpack_from("<Q", buffer, at + 1)[0]
            if opcode == 0:
                raise McapError(f"{where}: invalid opcode 0")
            start = at + 9
            if start + length > end:
                self._cut(where, f"record (opcode 0x{opcode:02x}, {length} bytes)", top_level)
                return
            fields = _Fields(buffer, start, start + length, where)
            if opcode == OP_SCHEMA:
                self._schema(fields)
            elif opcode == OP_CHANNEL:
                self._channel(fields)
            elif opcode == OP_MESSAGE:
                self._message(fields, where)
            elif opcode == OP_CHUNK:
                self._chunk(fields, at)
            elif opcode in (OP_DATA_END, OP_FOOTER) and top_level:
                return  # the summary repeats what the data section held
            at = start + length
        if top_level:
            self._cut(f"{self.path}: byte {at}", "DataEnd record", top_level)

    def _cut(self, where, what, top_level):
        if not top_level:
            raise McapError(f"{where}: {what} runs past the end of its chunk")
        self.truncated = True
        self.warnings.append(f"{where}: file truncated (no complete {what}); "
                             "read up to the last complete record")

    def _schema(self, fields):
        schema_id = fields.u16("schema id")
        name = fields.string("schema name")
        encoding = fields.string("schema encoding")
        self.schemas[schema_id] = Schema(schema_id, name, encoding, fields.bytes_u32("schema data"))

    def _channel(self, fields):
        channel_id = fields.u16("channel id")
        schema_id = fields.u16("channel schema id")
        topic = fields.string("channel topic")
        encoding = fields.string("channel message encoding")
        metadata = fields.string_map("channel metadata")
        self.channels[channel_id] = Channel(channel_id, schema_id, topic, encoding, metadata)

    def _message(self, fields, where):
        channel_id = fields.u16("message channel id")
        sequence = fields.u32("message sequence")
        log_time = fields.u64("message log time")
        publish_time = fields.u64("message publish time")
        channel = self.channels.get(channel_id)
        if channel is None:
            raise McapError(f"{where}: message on unknown channel {channel_id}")
        message = Message(channel, sequence, log_time, publish_time, fields.rest())
        self._messages.append((log_time, len(self._messages), message))

    def _chunk(self, fields, offset):
        fields.u64("chunk start time")
        fields.u64("chunk end time")
        size = fields.u64("chunk uncompressed size")
        crc = fields.u32("chunk uncompressed crc")
        compression = fields.string("chunk compression")
        records_size = fields.u64("chunk records length")
        records = fields.buffer[fields._take(records_size, "chunk records"):fields.at]
        where = f"{self.path}: byte {offset}: Chunk record"
        if compression:
            decompress = _DECOMPRESSORS.get(compression)
            if decompress is None:
                raise McapError(f"{where}: unknown compression '{compression}'")
            try:
                records = decompress(records, size)
            except McapError:
                raise
            except Exception as error:  # the decompressors' own exception types
                raise McapError(f"{where}: {compression} data does not decompress ({error})") \
                    from None
        if len(records) != size:
            raise McapError(f"{where}: decompressed to {len(records)} bytes, expected {size}")
        records = memoryview(bytes(records))
        if crc != 0 and zlib.crc32(records) != crc:
            raise McapError(f"{where}: CRC mismatch (stored 0x{crc:08x}, "
                            f"computed 0x{zlib.crc32(records):08x})")
        self._scan(records, 0, len(records), top_level=False, chunk_offset=offset)
