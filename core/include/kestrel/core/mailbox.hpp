#pragma once
// A one-slot mailbox between two threads: one producer fills the slot in place and posts it,
// one consumer reads it in place and empties it. Neither waits: a producer that finds the slot
// still full skips this message (the next one will be newer), a consumer that finds it empty
// has nothing to do. In place, because the messages are whole scans (kilobytes) that a queue
// would copy twice; one slot, because the consumer wants the newest scan, not a backlog.
//
// The slot's contents belong to the producer while the mailbox is empty and to the consumer
// while it is full; the release/acquire pair on the flag hands them over.
#include <atomic>

namespace kestrel {

template <class T>
class Mailbox {
 public:
  // Producer: the slot to fill, or nullptr while the consumer holds it. post() hands it over.
  T* writable() { return full_.load(std::memory_order_acquire) ? nullptr : &slot_; }
  void post() { full_.store(true, std::memory_order_release); }

  // Consumer: the message, or nullptr while the slot is empty. done() gives the slot back.
  T* readable() { return full_.load(std::memory_order_acquire) ? &slot_ : nullptr; }
  void done() { full_.store(false, std::memory_order_release); }

  // Either side: whether a message waits (for the other mailbox's side of a hand-shake). Two
  // mailboxes used as a request and its reply: the replier posts the reply before it frees
  // the request's slot, so the requester must find the request slot free first and read this
  // flag after; the other order can miss a reply posted in between.
  bool full() const { return full_.load(std::memory_order_acquire); }
  // Start-up only, with neither side running.
  void clear() { full_.store(false, std::memory_order_relaxed); }

 private:
  T slot_{};
  std::atomic<bool> full_{false};
};

}  // namespace kestrel
