#include "interactive_prompt.h"

#include <google/protobuf/util/json_util.h>

#include <istream>
#include <ostream>
#include <string>

#include "dccl/message_json.h"
#include "message_builder.h"
#include "output.h"
#include "rpc_error.h"

namespace acomms::cli {
namespace gp = google::protobuf;

namespace {

using F = gp::FieldDescriptor;

class Prompter {
 public:
  Prompter(TypeSchema& schema, const PromptStreams& streams)
      : schema_(schema), streams_(streams) {}

  void fill(gp::Message& message, const std::string& prefix);

 private:
  void ask_scalar(gp::Message& message, const F* field, const std::string& path);
  void ask_message(gp::Message& message, const F* field, const std::string& path);
  bool ask_yes_no(const std::string& question);
  std::string read_answer(const std::string& path);
  std::string describe(const F* field, const dccl::FieldOptions& bounds) const;
  std::string bound_violation(const gp::Message& holder, const F* field, const dccl::FieldOptions& bounds) const;

  TypeSchema& schema_;
  PromptStreams streams_;
};

std::string trim(const std::string& text) {
  size_t begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  return text.substr(begin, text.find_last_not_of(" \t\r") - begin + 1);
}

// One line of input, trimmed; false at the end of the input.
bool read_line(const PromptStreams& streams, std::string* answer) {
  if (!std::getline(streams.in, *answer)) {
    if (streams.echo) streams.out << "\n";
    return false;
  }
  *answer = trim(*answer);
  if (streams.echo) streams.out << *answer << "\n";
  return true;
}

bool is_number(const F* field) {
  switch (field->cpp_type()) {
    case F::CPPTYPE_INT32: case F::CPPTYPE_INT64: case F::CPPTYPE_UINT32:
    case F::CPPTYPE_UINT64: case F::CPPTYPE_DOUBLE: case F::CPPTYPE_FLOAT:
      return true;
    default:
      return false;
  }
}

// Element `index` (or the singular value when index < 0) as a double, for
// comparing with DCCL's bounds, which are doubles too.
double number_at(const gp::Message& message, const F* field, int index) {
  const gp::Reflection* r = message.GetReflection();
  const bool rep = index >= 0;
  switch (field->cpp_type()) {
    case F::CPPTYPE_INT32: return rep ? r->GetRepeatedInt32(message, field, index) : r->GetInt32(message, field);
    case F::CPPTYPE_INT64:
      return static_cast<double>(rep ? r->GetRepeatedInt64(message, field, index) : r->GetInt64(message, field));
    case F::CPPTYPE_UINT32: return rep ? r->GetRepeatedUInt32(message, field, index) : r->GetUInt32(message, field);
    case F::CPPTYPE_UINT64:
      return static_cast<double>(rep ? r->GetRepeatedUInt64(message, field, index) : r->GetUInt64(message, field));
    case F::CPPTYPE_FLOAT: return rep ? r->GetRepeatedFloat(message, field, index) : r->GetFloat(message, field);
    default: return rep ? r->GetRepeatedDouble(message, field, index) : r->GetDouble(message, field);
  }
}

size_t length_at(const gp::Message& message, const F* field, int index) {
  const gp::Reflection* r = message.GetReflection();
  return (index >= 0 ? r->GetRepeatedString(message, field, index) : r->GetString(message, field)).size();
}

std::string Prompter::describe(const F* field, const dccl::FieldOptions& bounds) const {
  std::string text = field_type_text(field);
  if (field->type() == F::TYPE_BYTES) text += " as hex 0x...";
  if (field->is_repeated()) {
    text += ", comma-separated";
  } else {
    text += field->is_required() ? ", required" : ", optional";
  }
  std::string limits;
  auto add = [&](const std::string& item) { limits += (limits.empty() ? "" : ", ") + item; };
  if (bounds.has_min) add("min " + number_text(bounds.min));
  if (bounds.has_max) add("max " + number_text(bounds.max));
  if (bounds.has_precision) add("precision " + std::to_string(bounds.precision));
  if (bounds.has_resolution) add("resolution " + number_text(bounds.resolution));
  if (bounds.has_max_length) add("max_length " + std::to_string(bounds.max_length));
  if (bounds.min_repeat > 0) add("min_repeat " + std::to_string(bounds.min_repeat));
  if (bounds.has_max_repeat) add("max_repeat " + std::to_string(bounds.max_repeat));
  if (field->enum_type() != nullptr) add("one of " + enum_value_names(field->enum_type()));
  return limits.empty() ? text : text + "; " + limits;
}

// The daemon would refuse these (strict) or silently change them (DCCL
// zeroes out-of-range values), so the person is asked again instead.
std::string Prompter::bound_violation(const gp::Message& holder, const F* field,
                                      const dccl::FieldOptions& bounds) const {
  const gp::Reflection* r = holder.GetReflection();
  const int count = field->is_repeated() ? r->FieldSize(holder, field) : 1;
  if (field->is_repeated()) {
    if (bounds.has_max_repeat && count > static_cast<int>(bounds.max_repeat)) {
      return std::to_string(count) + " values, more than max_repeat " + std::to_string(bounds.max_repeat);
    }
    if (count > 0 && count < static_cast<int>(bounds.min_repeat)) {
      return std::to_string(count) + " values, fewer than min_repeat " + std::to_string(bounds.min_repeat);
    }
  }
  for (int i = 0; i < count; ++i) {
    const int index = field->is_repeated() ? i : -1;
    if (is_number(field)) {
      double value = number_at(holder, field, index);
      if (bounds.has_min && value < bounds.min) return number_text(value) + " is below min " + number_text(bounds.min);
      if (bounds.has_max && value > bounds.max) return number_text(value) + " is above max " + number_text(bounds.max);
    } else if (field->cpp_type() == F::CPPTYPE_STRING && bounds.has_max_length) {
      size_t length = length_at(holder, field, index);
      if (length > bounds.max_length) {
        return std::to_string(length) + " bytes, more than max_length " + std::to_string(bounds.max_length);
      }
    }
  }
  return "";
}

std::string Prompter::read_answer(const std::string& path) {
  std::string line;
  if (!read_line(streams_, &line)) throw UsageError("input ended while asking for " + path);
  return line;
}

bool Prompter::ask_yes_no(const std::string& question) {
  streams_.out << question << " [y/N] " << std::flush;
  std::string answer = read_answer(question);
  return answer == "y" || answer == "Y" || answer == "yes";
}

void Prompter::ask_scalar(gp::Message& message, const F* field, const std::string& path) {
  const dccl::FieldOptions bounds = schema_.field_options(field);
  while (true) {
    streams_.out << path << " (" << describe(field, bounds) << "): " << std::flush;
    std::string answer = read_answer(path);
    // Even a required field may be left empty: the daemon fills its queue
    // role fields (source, time) and names any that are still missing.
    if (answer.empty()) return;
    // Parsed into a scratch copy first: a refused answer leaves nothing behind.
    std::unique_ptr<gp::Message> scratch(message.New());
    try {
      set_field(*scratch, field, answer);
    } catch (const UsageError& e) {
      streams_.out << "  ! " << e.what() << "\n";
      continue;
    }
    std::string violation = bound_violation(*scratch, field, bounds);
    if (!violation.empty()) {
      streams_.out << "  ! " << violation << "\n";
      continue;
    }
    message.GetReflection()->SwapFields(&message, scratch.get(), {field});
    return;
  }
}

// Required sub-messages are filled; optional and repeated ones only when
// the person says so, which keeps piped answers predictable.
void Prompter::ask_message(gp::Message& message, const F* field, const std::string& path) {
  const gp::Reflection* r = message.GetReflection();
  if (!field->is_repeated()) {
    if (!field->is_required() && !ask_yes_no(path + " (" + field_type_text(field) + ", optional): fill it?")) return;
    fill(*r->MutableMessage(&message, field), path + ".");
    return;
  }
  const dccl::FieldOptions bounds = schema_.field_options(field);
  for (int i = 0; !bounds.has_max_repeat || i < static_cast<int>(bounds.max_repeat); ++i) {
    const std::string element = path + "[" + std::to_string(i) + "]";
    if (!ask_yes_no("add " + element + " (" + field->message_type()->name() + ")?")) return;
    fill(*r->AddMessage(&message, field), element + ".");
  }
}

void Prompter::fill(gp::Message& message, const std::string& prefix) {
  const gp::Descriptor* type = message.GetDescriptor();
  for (int i = 0; i < type->field_count(); ++i) {
    const F* field = type->field(i);
    const std::string path = prefix + field->name();
    if (schema_.field_options(field).omit) {
      streams_.out << path << ": (dccl.field).omit, not sent\n";
      continue;
    }
    if (field->message_type() != nullptr) {
      ask_message(message, field, path);
    } else {
      ask_scalar(message, field, path);
    }
  }
}

}  // namespace

std::unique_ptr<gp::Message> prompt_message(TypeSchema& schema, const PromptStreams& streams) {
  std::unique_ptr<gp::Message> message = schema.new_message();
  streams.out << schema.type()->full_name() << ": one value per line; an empty line skips a field\n"
              << "(the daemon fills its queue role fields, such as source and time, and names any required "
                 "field still missing)\n";
  Prompter(schema, streams).fill(*message, "");
  return message;
}

bool confirm_send(const gp::Message& message, const PromptStreams& streams) {
  // Partial-safe: required fields the daemon fills (source, time) are unset here.
  std::string json = dccl::indented_message_json(message);
  streams.out << json << (json.empty() || json.back() != '\n' ? "\n" : "") << "send? [y/N] " << std::flush;
  std::string answer;
  if (!read_line(streams, &answer)) return false;
  return answer == "y" || answer == "Y" || answer == "yes";
}

}  // namespace acomms::cli
