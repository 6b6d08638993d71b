#pragma once
// Ctrl+Z and Ctrl+Shift+Z in the viewer: each step of the history is the
// engine-thread command that undoes one of the user's actions (a gizmo drag,
// a colour or light edit) and the command that does it again. Undoing a move
// moves the object back, which returns the earlier solution (the update is
// path-independent: README, "The update after a move").

#include <optional>
#include <vector>

#include "viewer/EngineThread.h"

namespace rad::viewer {

class UndoHistory {
  public:
    struct Step {
        Command undo;
        Command redo;
    };
    // A new action: what was undone before cannot be redone any more.
    void record(const Command& undo, const Command& redo) {
        done_.push_back(Step{undo, redo});
        undone_.clear();
    }
    // The command to post, or none when there is nothing to undo (redo).
    std::optional<Command> undo() { return move(done_, undone_, &Step::undo); }
    std::optional<Command> redo() { return move(undone_, done_, &Step::redo); }

  private:
    static std::optional<Command> move(std::vector<Step>& from, std::vector<Step>& to, Command Step::*which) {
        if (from.empty()) return std::nullopt;
        to.push_back(std::move(from.back()));
        from.pop_back();
        return to.back().*which;
    }
    std::vector<Step> done_, undone_;
};

}  // namespace rad::viewer
