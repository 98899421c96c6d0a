#include "app/viewer/morph_tool.h"

#include "app/viewer/key_bindings.h"

namespace trilab::viewer {

MorphTool::MorphTool(ViewerContext& context) : Tool(context) {
    context.record = &record_;
}

MorphTool::~MorphTool() {
    if (context_.record == &record_) context_.record = nullptr;
}

void MorphTool::section(const SidebarContext& context, CommandQueue& commands) {
    if (context.history && context.morph)
        morph_section(morph_open_, *context.morph, *context.history, commands);
    record_section(record_, context.can_record, context.record_why_not, commands);
}

PanelEntries MorphTool::panels() {
    PanelEntry morph;
    morph.name = "morph";
    morph.title = "Morph";
    morph.open = &morph_open_;
    morph.menu = PanelMenu::Edit;
    morph.shortcut = int(KeyAction::ToggleMorph);
    PanelEntry record;
    record.name = "record";
    record.title = "Record";
    record.open = &record_.open;
    record.menu = PanelMenu::Edit;
    record.shortcut = int(KeyAction::ToggleRecord);
    return {morph, record};
}

void MorphTool::settings(SettingsVisitor& v) {
    v.number("record.frames", record_.frames);
    v.number("record.fps", record_.fps);
    v.number("record.width", record_.width);
    v.number("record.height", record_.height);
    v.text("record.folder", record_.folder);
    v.text("record.name", record_.name);
    v.flag("record.mp4", record_.mp4);
}

}  // namespace trilab::viewer
