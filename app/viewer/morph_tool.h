#pragma once
// MorphTool: the Morph and Record sections. The morph is the session's (every control queues
// a command: PlayMorph, ShowMorphAt, SetMorphAnimation); the tool owns whether the sections
// are open and the Record settings, which FrameOutput reads while it writes the frames
// (ViewerContext::record points at them).
#include "app/viewer/tool.h"

namespace trilab::viewer {

class MorphTool : public Tool {
public:
    explicit MorphTool(ViewerContext& context);
    ~MorphTool() override;
    void section(const SidebarContext& context, CommandQueue& commands) override;
    PanelEntries panels() override;
    void settings(SettingsVisitor& v) override;
    bool& morph_open() { return morph_open_; }
    RecordState& record() { return record_; }

private:
    bool morph_open_ = false;
    RecordState record_;
};

}  // namespace trilab::viewer
