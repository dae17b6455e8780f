"""wbi recordings (.mcap with omgidl schemas and CDR messages) as numpy arrays.

    rec = Recording("run.mcap")
    rec.topics                                   # ["wbi/arm/sensors", "wbi/arm/state", ...]
    state = rec.topic("wbi/arm/state")           # TopicData, decoded on first use
    state.t                                      # log time [s] since the recording's first message
    state["q"]                                   # (N, n) array; state["header.seq"]: (N,)
    state.fields                                 # every field path
    q_on_sensor_times = state.at(rec.topic("wbi/arm/sensors").t, "q")   # zero-order hold

Field paths join member names with '.'; a sequence or array of numbers is one
field with a column per element (rows padded with NaN when the length
changes); a sequence of structs gives one field per leaf, a column per
element ("force_torque.force.x"). Strings come as object arrays, enums as
their integer values (`enum_names(field)` maps them to names). All topics share
one time base (log time, `t`), so they are aligned by construction; `at()`
resamples a field onto other times.
"""

import numpy as np

from .cdr import CdrDecoder
from .mcap import McapReader
from .omgidl import Enum, Sequence, Array, Struct, parse_idl, resolve

__all__ = ["Recording", "TopicData", "RecordingError"]


class RecordingError(Exception):
    """A topic or field that the recording does not have, or cannot decode."""


def _join(prefix, name):
    return f"{prefix}.{name}" if prefix and name else prefix or name


def _leaves(kind, prefix=""):
    """Field paths of a type's leaves, as _flatten writes them."""
    if isinstance(kind, Struct):
        return [leaf for name, member in kind.members
                for leaf in _leaves(member, _join(prefix, name))]
    if isinstance(kind, (Sequence, Array)) and isinstance(kind.element, Struct):
        return _leaves(kind.element, prefix)
    return [prefix]


def _flatten(kind, value, prefix, out):
    """Leaf path -> scalar, string, numpy vector or list, for one decoded sample; driven by
    the type, so every sample has the same paths (also with empty sequences)."""
    if isinstance(kind, Struct):
        for name, member in kind.members:
            _flatten(member, value[name], _join(prefix, name), out)
    elif isinstance(kind, (Sequence, Array)) and isinstance(kind.element, Struct):
        elements = []
        for element in value:
            flat = {}
            _flatten(kind.element, element, "", flat)
            elements.append(flat)
        for leaf in _leaves(kind.element):
            out[_join(prefix, leaf)] = [flat[leaf] for flat in elements]
    else:
        out[prefix] = value


def _stack(rows):
    """Rows of one field (scalars, or vectors of varying length) as an array."""
    first = rows[0]
    if isinstance(first, str) or (isinstance(first, list) and first and isinstance(first[0], str)):
        result = np.empty(len(rows), dtype=object)
        result[:] = rows
        return result
    if np.ndim(first) == 0:
        return np.asarray(rows)
    arrays = [np.asarray(row).reshape(-1) for row in rows]
    width = max(array.size for array in arrays)
    if all(array.size == width for array in arrays):
        return np.stack(arrays) if arrays else np.empty((0, width))
    padded = np.full((len(arrays), width), np.nan)
    for index, array in enumerate(arrays):
        padded[index, :array.size] = array
    return padded


def _enum_fields(kind, prefix, out):
    """Field path -> Enum for every enum leaf of a type."""
    if isinstance(kind, Struct):
        for name, member in kind.members:
            _enum_fields(member, f"{prefix}.{name}" if prefix else name, out)
    elif isinstance(kind, (Sequence, Array)):
        _enum_fields(kind.element, prefix, out)
    elif isinstance(kind, Enum):
        out[prefix] = kind


class TopicData:
    """The messages of one topic: times and one array per field."""

    def __init__(self, topic, type_name, start_ns, messages, decoder, enums):
        self.topic = topic
        self.type_name = type_name
        self.log_time_ns = np.array([m.log_time for m in messages], dtype=np.int64)
        self.publish_time_ns = np.array([m.publish_time for m in messages], dtype=np.int64)
        self.t = (self.log_time_ns - start_ns) * 1e-9
        self._enums = enums
        rows = {leaf: [] for leaf in _leaves(decoder.kind)}
        for index, message in enumerate(messages):
            flat = {}
            try:
                _flatten(decoder.kind, decoder(message.data), "", flat)
            except Exception as error:
                raise RecordingError(f"{topic}: message {index} (log time {message.log_time}): "
                                     f"{error}") from None
            for key, value in flat.items():
                rows[key].append(value)
        self._fields = {key: _stack(values) for key, values in rows.items() if values}

    def __len__(self):
        return self.t.size

    @property
    def fields(self):
        return sorted(self._fields)

    def __getitem__(self, field):
        return self.field(field)

    def field(self, field):
        """The array of a field path: one row per message."""
        if field not in self._fields:
            raise RecordingError(f"{self.topic} ({self.type_name}) has no field '{field}'; it has: "
                                 + ", ".join(self.fields))
        return self._fields[field]

    def enum_names(self, field):
        """{value: name} of an enum field."""
        enum = self._enums.get(field)
        if enum is None:
            raise RecordingError(f"{self.topic}: field '{field}' is not an enum")
        return dict(enum.enumerators)

    def at(self, times, field):
        """A numeric field resampled onto `times` [s, the recording's time base]: the last
        message at or before each time (zero-order hold); NaN before the first message."""
        values = np.asarray(self.field(field), dtype=float)
        index = np.searchsorted(self.t, np.asarray(times, dtype=float), side="right") - 1
        result = values[np.clip(index, 0, None)].copy() if len(values) else \
            np.full((len(times),) + values.shape[1:], np.nan)
        result[index < 0] = np.nan
        return result


class Recording:
    """A wbi recording; topics are decoded on first use."""

    def __init__(self, path):
        self.path = str(path)
        self.reader = McapReader(path)
        self._by_topic = {}
        for message in self.reader.messages():
            self._by_topic.setdefault(message.channel.topic, []).append(message)
        times = [messages[0].log_time for messages in self._by_topic.values()]
        self.start_ns = min(times) if times else 0
        self.end_ns = max((m[-1].log_time for m in self._by_topic.values()), default=0)
        self._decoded = {}

    @property
    def topics(self):
        """Topics with at least one message."""
        return sorted(self._by_topic)

    @property
    def duration_s(self):
        return (self.end_ns - self.start_ns) * 1e-9

    @property
    def truncated(self):
        return self.reader.truncated

    @property
    def warnings(self):
        return list(self.reader.warnings)

    def topic(self, topic):
        """The TopicData of a topic."""
        if topic not in self._decoded:
            messages = self._by_topic.get(topic)
            if messages is None:
                raise RecordingError(f"{self.path}: no messages on topic '{topic}'; topics: "
                                     + ", ".join(self.topics))
            channel = messages[0].channel
            schema = self.reader.schemas.get(channel.schema_id)
            if channel.message_encoding != "cdr" or schema is None or schema.encoding != "omgidl":
                raise RecordingError(
                    f"{self.path}: topic '{topic}' is encoded as '{channel.message_encoding}' "
                    f"with schema encoding '{schema.encoding if schema else 'none'}'; "
                    "only cdr messages with omgidl schemas are decoded")
            try:
                kind = resolve(parse_idl(schema.data.decode("utf-8")), schema.name)
            except Exception as error:
                raise RecordingError(f"{self.path}: schema '{schema.name}' of topic '{topic}': "
                                     f"{error}") from None
            enums = {}
            _enum_fields(kind, "", enums)
            self._decoded[topic] = TopicData(topic, schema.name, self.start_ns, messages,
                                             CdrDecoder(kind, schema.name), enums)
        return self._decoded[topic]

    def __getitem__(self, topic):
        return self.topic(topic)
