// holoray/live: `holoray live --events FILE`, input replayed by frame number
// (docs/guide/live.md, "Scripted runs"), for tests and demos. One event a
// line, '#' to the line's end a comment:
//
//     FRAME orbit DX DY    a left-button drag by DX, DY pixels (y down)
//     FRAME pan DX DY      a shift-drag
//     FRAME pointer X Y    the pointer at X, Y (no button held: --simulate's eye)
//     FRAME wheel CLICKS   the wheel (up > 0)
//     FRAME key NAME       a key, named as the guide's table names it
//
// FRAME >= 1: the event is applied before that frame (counting from 0) is
// rendered; frames ascend.
#pragma once

#include <string>
#include <vector>

#include "live/window.hpp"

namespace holoray::live {

struct ScriptedEvent {
  int frame = 0;
  InputEvent event;
};

/// The file's events in order. Throws ParseError (file:line:col, what was
/// expected) for a malformed line, std::system_error when unreadable.
std::vector<ScriptedEvent> read_event_script(const std::string& path);

/// Whether `name` is a key live acts on ("S", "shift+S", "Up", ...).
bool is_live_key(const std::string& name);

}  // namespace holoray::live
