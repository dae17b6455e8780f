// Message iteration over an opened MCAP file (Reader::messages): chunks loaded
// on demand, in file order or merged into log-time order.
#include <algorithm>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "reader_impl.hpp"

namespace wbi::mcap {

using namespace detail;

// ---------------------------------------------------------------------------
// Message iteration

struct MessageCursor::State {
  // A loaded block: its records (in the file or in buffer) and, in log-time
  // order, how many of its messages are still in the heap.
  struct Slot {
    std::uint64_t offset = 0;
    bool chunk = false;
    std::span<const std::uint8_t> records;
    ByteBuffer buffer;
    std::size_t pending = 0;
  };
  // A message waiting in the log-time heap; ordered by (log_time, offset, at).
  struct Entry {
    std::uint64_t log_time;
    std::uint64_t offset;  // of its block
    std::uint64_t at;      // in the block's records
    std::uint32_t slot;
  };
  static bool later(const Entry& a, const Entry& b) {
    return std::tie(a.log_time, a.offset, a.at) > std::tie(b.log_time, b.offset, b.at);
  }

  const Reader::Impl* reader = nullptr;
  Order order = Order::log_time;
  std::vector<Block> blocks;
  std::size_t next_block = 0;
  std::vector<Slot> slots;
  std::vector<std::uint32_t> free_slots;
  std::vector<Entry> heap;
  std::optional<std::uint32_t> returned_slot;  // holds the data of the last returned message
  std::uint64_t file_at = 0;                   // file order: next record in slots[0]
  MessageView view;
  detail::Decompressor decompressor;

  // Loads blocks[next_block++] into a free slot; returns the slot.
  std::uint32_t load_next() {
    const Block& block = blocks[next_block++];
    std::uint32_t index = 0;
    if (free_slots.empty()) {
      index = static_cast<std::uint32_t>(slots.size());
      slots.emplace_back();
    } else {
      index = free_slots.back();
      free_slots.pop_back();
    }
    Slot& slot = slots[index];
    slot.offset = block.offset;
    slot.chunk = block.chunk;
    slot.pending = 0;
    if (block.chunk) {
      const ChunkHeader chunk = reader->chunk_at(block.offset);
      slot.records = reader->chunk_records(block.offset, chunk, slot.buffer, decompressor);
    } else {
      // A Message record outside chunks: its record is the block's only record.
      const auto length = detail::load_le<std::uint64_t>(reader->bytes().data() + block.offset + 1);
      slot.records = reader->bytes().subspan(block.offset, kRecordHeader + length);
    }
    return index;
  }

  // Fills view from the Message record content at byte `at` of a slot's records.
  void make_view(const Slot& slot, std::span<const std::uint8_t> content, std::uint64_t at) {
    const Where where = slot.chunk ? Where{slot.offset, at} : Where{slot.offset, {}};
    const auto m = reader->parse(as_byte(Opcode::message), content, where, message_fields);
    const auto channel = reader->info.channels.find(m.channel_id);
    if (channel == reader->info.channels.end()) {
      throw reader->error(slot.offset, "Message record" + where_text(where) +
                                           ": unknown channel id " + std::to_string(m.channel_id));
    }
    view.channel = &channel->second;
    view.schema = nullptr;
    if (channel->second.schema_id != 0) {
      const auto schema = reader->info.schemas.find(channel->second.schema_id);
      view.schema = schema == reader->info.schemas.end() ? nullptr : &schema->second;
    }
    view.sequence = m.sequence;
    view.log_time = m.log_time;
    view.publish_time = m.publish_time;
    view.data = m.data;
  }

  void release(std::uint32_t index) {
    if (--slots[index].pending == 0) {
      free_slots.push_back(index);
    }
  }

  const MessageView* next_in_file_order();
  const MessageView* next_in_log_time_order();
};

const MessageView* MessageCursor::State::next_in_file_order() {
  // slots[0] is the current block; file_at the next record in it.
  for (;;) {
    if (!slots.empty()) {
      Slot& slot = slots[0];
      while (file_at < slot.records.size()) {
        const std::uint64_t at = file_at;
        const std::uint64_t left = slot.records.size() - at;
        if (left < kRecordHeader) {
          throw reader->error(slot.offset, "Chunk record: stray bytes at the end of its records");
        }
        const std::uint8_t opcode = slot.records[at];
        const auto length = detail::load_le<std::uint64_t>(slot.records.data() + at + 1);
        if (length > left - kRecordHeader) {
          throw reader->error(slot.offset, "Chunk record: the " + opcode_name(opcode) +
                                               " record at byte " + std::to_string(at) +
                                               " of its records runs past their end");
        }
        file_at += kRecordHeader + length;
        if (opcode == as_byte(Opcode::message)) {
          make_view(slot, slot.records.subspan(at + kRecordHeader, length), at);
          return &view;
        }
      }
    }
    if (next_block == blocks.size()) {
      return nullptr;
    }
    free_slots.clear();
    if (!slots.empty()) {
      free_slots.push_back(0);
    }
    load_next();
    file_at = 0;
  }
}

const MessageView* MessageCursor::State::next_in_log_time_order() {
  if (returned_slot) {
    release(*returned_slot);
    returned_slot.reset();
  }
  // Load every block that may hold a message before the heap's earliest.
  while (next_block < blocks.size() &&
         (heap.empty() || blocks[next_block].start_time <= heap.front().log_time)) {
    const std::uint32_t index = load_next();
    Slot& slot = slots[index];
    reader->for_each_chunk_record(
        slot.offset, slot.records,
        [&](std::uint8_t opcode, std::span<const std::uint8_t> content, std::uint64_t at) {
          if (opcode != as_byte(Opcode::message)) {
            return;
          }
          if (content.size() < kMessageFields) {
            make_view(slot, content, at);  // throws the field error
          }
          const auto log_time = detail::load_le<std::uint64_t>(content.data() + 6);
          heap.push_back({log_time, slot.offset, at, index});
          std::push_heap(heap.begin(), heap.end(), later);
          ++slot.pending;
        });
    if (slot.pending == 0) {
      free_slots.push_back(index);
    }
  }
  if (heap.empty()) {
    return nullptr;
  }
  std::pop_heap(heap.begin(), heap.end(), later);
  const Entry entry = heap.back();
  heap.pop_back();
  const Slot& slot = slots[entry.slot];
  const auto length = detail::load_le<std::uint64_t>(slot.records.data() + entry.at + 1);
  make_view(slot, slot.records.subspan(entry.at + kRecordHeader, length), entry.at);
  returned_slot = entry.slot;
  return &view;
}

MessageCursor::MessageCursor(std::unique_ptr<State> state) : state_(std::move(state)) {}
MessageCursor::~MessageCursor() = default;
MessageCursor::MessageCursor(MessageCursor&&) noexcept = default;
MessageCursor& MessageCursor::operator=(MessageCursor&&) noexcept = default;

const MessageView* MessageCursor::next() {
  return state_->order == Order::file ? state_->next_in_file_order()
                                      : state_->next_in_log_time_order();
}

MessageCursor Reader::messages(Order order) const {
  auto state = std::make_unique<MessageCursor::State>();
  state->reader = impl_.get();
  state->order = order;
  state->blocks = impl_->blocks;
  if (order == Order::log_time) {
    std::stable_sort(state->blocks.begin(), state->blocks.end(),
                     [](const Block& a, const Block& b) { return a.start_time < b.start_time; });
  }
  return MessageCursor(std::move(state));
}

}  // namespace wbi::mcap
