#include "core/fleet_render.h"

#include <google/protobuf/text_format.h>

namespace acomms::core {

namespace {

namespace pb = google::protobuf;

class Renderer {
 public:
  explicit Renderer(const Provenance* where) : where_(where) {}

  void message(const pb::Message& message, const std::string& prefix, int depth) {
    std::vector<const pb::FieldDescriptor*> fields;
    message.GetReflection()->ListFields(message, &fields);
    for (const pb::FieldDescriptor* field : fields) {
      const int count = field->is_repeated() ? message.GetReflection()->FieldSize(message, field) : 1;
      for (int i = 0; i < count; ++i) {
        const int index = field->is_repeated() ? i : -1;
        const std::string path = field->is_repeated() ? prefix + field->name() + "[" + std::to_string(i) + "]"
                                                      : prefix + field->name();
        const std::string indent(2 * depth, ' ');
        if (field->cpp_type() == pb::FieldDescriptor::CPPTYPE_MESSAGE) {
          line(indent + std::string(field->name()) + " {", path);
          const pb::Message& sub = field->is_repeated() ? message.GetReflection()->GetRepeatedMessage(message, field, i)
                                                        : message.GetReflection()->GetMessage(message, field);
          this->message(sub, path + ".", depth + 1);
          line(indent + "}", "");
        } else {
          std::string value;
          pb::TextFormat::Printer printer;
          printer.SetSingleLineMode(true);
          printer.PrintFieldValueToString(message, field, index, &value);
          line(indent + std::string(field->name()) + ": " + value, path);
        }
      }
    }
  }

  RenderedText result() && { return std::move(out_); }

 private:
  void line(const std::string& text, const std::string& path) {
    out_.text += text;
    if (where_ != nullptr && !path.empty()) {
      auto it = where_->find(path);
      out_.text += "  # " + (it == where_->end() ? std::string("(default)") : to_string(it->second));
    }
    out_.text += "\n";
    out_.line_paths.push_back(path);
  }

  const Provenance* where_;
  RenderedText out_;
};

}  // namespace

RenderedText render_located(const pb::Message& message, const Provenance* where) {
  Renderer renderer(where);
  renderer.message(message, "", 0);
  return std::move(renderer).result();
}

}  // namespace acomms::core
