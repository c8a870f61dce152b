#include "mocaplink/wire/qtm_parameters.hpp"

#include <charconv>
#include <cstdint>
#include <set>
#include <utility>

namespace mocaplink::wire::qtm {

namespace {

struct Attribute {
  std::string name;
  std::string value;
};

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

bool is_name_char(char c) {
  return !is_space(c) && c != '/' && c != '>' && c != '=' && c != '<' && c != '"' && c != '\'';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

// Text with character references resolved; false on an unknown or malformed reference.
bool decode_text(std::string_view raw, std::string& out) {
  out.clear();
  out.reserve(raw.size());
  while (!raw.empty()) {
    const auto amp = raw.find('&');
    out += raw.substr(0, amp);
    if (amp == std::string_view::npos) break;
    raw.remove_prefix(amp + 1);
    const auto semi = raw.find(';');
    if (semi == std::string_view::npos || semi > 10) return false;
    const std::string_view ref = raw.substr(0, semi);
    raw.remove_prefix(semi + 1);
    if (ref == "lt") {
      out += '<';
    } else if (ref == "gt") {
      out += '>';
    } else if (ref == "amp") {
      out += '&';
    } else if (ref == "quot") {
      out += '"';
    } else if (ref == "apos") {
      out += '\'';
    } else if (ref.size() >= 2 && ref[0] == '#') {
      const bool hex = ref[1] == 'x' || ref[1] == 'X';
      const std::string_view digits = ref.substr(hex ? 2 : 1);
      std::uint32_t cp = 0;
      const auto [end, ec] =
          std::from_chars(digits.data(), digits.data() + digits.size(), cp, hex ? 16 : 10);
      if (digits.empty() || ec != std::errc{} || end != digits.data() + digits.size() || cp == 0 ||
          cp > 0x10FFFF) {
        return false;
      }
      append_utf8(out, cp);
    } else {
      return false;
    }
  }
  return true;
}

std::string escape(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// Collects what Parameters needs from the element events of the reader below.
class Collector {
 public:
  explicit Collector(Parameters& out) : out_(out) {}

  // `path`: element names from the root (path[0]) to the new element.
  void start(const std::vector<std::string>& path, const std::vector<Attribute>& attributes) {
    const std::size_t d = path.size();
    if (d == 1) out_.root = path[0];
    if (d == 2 && path[1] == "The_6D") out_.has_6d = true;
    if (in_6d(path) && d == 3 && path[2] == "Body") {
      out_.bodies.emplace_back();
      body_named_.push_back(false);
    }
    if (d == 3 && path[1] == "General" && path[2] == "EulerAngles") {
      for (const auto& a : attributes) {
        if (a.name == "First") out_.euler_names[0] = a.value;
        if (a.name == "Second") out_.euler_names[1] = a.value;
        if (a.name == "Third") out_.euler_names[2] = a.value;
      }
    }
  }

  // The trimmed, decoded text directly inside the element at `path`, when it ends.
  std::string end(const std::vector<std::string>& path, std::string_view text) {
    const std::size_t d = path.size();
    if (d == 3 && path[1] == "General" && path[2] == "Frequency") {
      double hz = 0;
      const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), hz);
      if (ec == std::errc{} && p == text.data() + text.size()) out_.frequency_hz = hz;
    }
    if (!in_6d(path)) return {};
    if (d == 3 && path[2] == "Bodies") {
      std::size_t n = 0;
      const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
      if (ec != std::errc{} || p != text.data() + text.size()) {
        return "<Bodies> is not a count: \"" + std::string(text) + "\"";
      }
      out_.declared_bodies = n;
    }
    if (d == 3 && path[2] == "Body" && !body_named_.back()) return "a <Body> has no <Name>";
    if (d == 4 && path[2] == "Body" && !out_.bodies.empty()) {
      BodyParameters& body = out_.bodies.back();
      if (path[3] == "Name") {
        body.name = std::string(text);
        body_named_.back() = true;
      } else if (path[3] == "Enabled") {
        body.enabled = !(text == "false" || text == "False" || text == "0");
      } else if (path[3] == "Data_origin" || path[3] == "Data_orientation") {
        if (!text.empty() && text != "0") body.global = false;
      }
    }
    if (d == 4 && path[2] == "Euler") {
      if (path[3] == "First") out_.euler_names[0] = std::string(text);
      if (path[3] == "Second") out_.euler_names[1] = std::string(text);
      if (path[3] == "Third") out_.euler_names[2] = std::string(text);
    }
    return {};
  }

 private:
  static bool in_6d(const std::vector<std::string>& path) {
    return path.size() >= 2 && path[1] == "The_6D";
  }

  Parameters& out_;
  std::vector<bool> body_named_;
};

// The element reader: walks `xml` once, calling the collector; "" or the first problem.
class Reader {
 public:
  Reader(std::string_view xml, Collector& collector) : xml_(xml), collector_(collector) {}

  Result<bool> run() {
    while (pos_ < xml_.size()) {
      if (xml_[pos_] != '<') {
        const auto next = xml_.find('<', pos_);
        const auto raw = xml_.substr(pos_, next - pos_);
        if (!stack_.empty()) {
          text_.back() += raw;
        } else if (!trim(raw).empty() && trim(raw).find_first_not_of('\0') != std::string::npos) {
          return parse_error(pos_, "text outside the root element");
        }
        pos_ = next == std::string_view::npos ? xml_.size() : next;
        continue;
      }
      auto step = markup();
      if (!step) return step;
    }
    if (!stack_.empty()) return parse_error(pos_, "element <" + stack_.back() + "> not closed");
    if (!seen_root_) return parse_error(0, "no XML element");
    return true;
  }

 private:
  Result<bool> skip_to(std::string_view terminator, std::string_view what) {
    const auto end = xml_.find(terminator, pos_);
    if (end == std::string_view::npos) return parse_error(pos_, what.data());
    pos_ = end + terminator.size();
    return true;
  }

  Result<bool> markup() {
    const std::string_view rest = xml_.substr(pos_);
    if (rest.starts_with("<?")) return skip_to("?>", "unterminated processing instruction");
    if (rest.starts_with("<!--")) return skip_to("-->", "unterminated comment");
    if (rest.starts_with("<![CDATA[")) {
      const auto end = rest.find("]]>");
      if (end == std::string_view::npos) return parse_error(pos_, "unterminated CDATA");
      if (stack_.empty()) return parse_error(pos_, "CDATA outside the root element");
      text_.back() += escape(rest.substr(9, end - 9));  // verbatim once decoded
      pos_ += end + 3;
      return true;
    }
    if (rest.starts_with("<!")) return skip_to(">", "unterminated declaration");
    if (rest.starts_with("</")) return end_tag();
    return start_tag();
  }

  std::string read_name() {
    const std::size_t begin = pos_;
    while (pos_ < xml_.size() && is_name_char(xml_[pos_])) ++pos_;
    return std::string(xml_.substr(begin, pos_ - begin));
  }

  void skip_space() {
    while (pos_ < xml_.size() && is_space(xml_[pos_])) ++pos_;
  }

  Result<bool> start_tag() {
    const std::size_t at = pos_;
    ++pos_;  // '<'
    std::string name = read_name();
    if (name.empty()) return parse_error(at, "element without a name");
    if (stack_.empty() && seen_root_) return parse_error(at, "a second root element");
    if (stack_.size() >= kMaxXmlDepth) return parse_error(at, "elements nested too deep");
    std::vector<Attribute> attributes;
    bool self_closing = false;
    while (true) {
      skip_space();
      if (pos_ >= xml_.size()) return parse_error(at, "unterminated tag <" + name + ">");
      if (xml_[pos_] == '>') {
        ++pos_;
        break;
      }
      if (xml_[pos_] == '/') {
        if (pos_ + 1 >= xml_.size() || xml_[pos_ + 1] != '>') return parse_error(pos_, "stray /");
        pos_ += 2;
        self_closing = true;
        break;
      }
      Attribute a;
      a.name = read_name();
      skip_space();
      if (a.name.empty() || pos_ >= xml_.size() || xml_[pos_] != '=') {
        return parse_error(pos_, "bad attribute in <" + name + ">");
      }
      ++pos_;
      skip_space();
      if (pos_ >= xml_.size() || (xml_[pos_] != '"' && xml_[pos_] != '\'')) {
        return parse_error(pos_, "attribute value without quotes in <" + name + ">");
      }
      const char quote = xml_[pos_++];
      const auto close = xml_.find(quote, pos_);
      if (close == std::string_view::npos) return parse_error(pos_, "unterminated attribute");
      if (!decode_text(xml_.substr(pos_, close - pos_), a.value)) {
        return parse_error(pos_, "bad character reference in an attribute");
      }
      pos_ = close + 1;
      attributes.push_back(std::move(a));
    }
    seen_root_ = true;
    stack_.push_back(std::move(name));
    text_.emplace_back();
    collector_.start(stack_, attributes);
    if (self_closing) return close_element(at);
    return true;
  }

  Result<bool> end_tag() {
    const std::size_t at = pos_;
    pos_ += 2;
    const std::string name = read_name();
    skip_space();
    if (pos_ >= xml_.size() || xml_[pos_] != '>') return parse_error(at, "unterminated end tag");
    ++pos_;
    if (stack_.empty() || stack_.back() != name) {
      return parse_error(
          at, "</" + name + "> does not close " +
                  (stack_.empty() ? std::string("anything") : "<" + stack_.back() + ">"));
    }
    return close_element(at);
  }

  Result<bool> close_element(std::size_t at) {
    std::string text;
    if (!decode_text(text_.back(), text)) {
      return parse_error(at, "bad character reference in <" + stack_.back() + ">");
    }
    if (auto problem = collector_.end(stack_, trim(text)); !problem.empty()) {
      return parse_error(at, problem);
    }
    stack_.pop_back();
    text_.pop_back();
    return true;
  }

  std::string_view xml_;
  Collector& collector_;
  std::size_t pos_ = 0;
  std::vector<std::string> stack_;
  std::vector<std::string> text_;  // direct text of each open element, undecoded
  bool seen_root_ = false;
};

}  // namespace

std::string Parameters::duplicate_name() const {
  std::set<std::string_view> seen;
  for (const auto& b : bodies) {
    if (!seen.insert(b.name).second) return b.name;
  }
  return {};
}

Result<Parameters> parse_parameters(std::string_view xml) {
  Parameters out;
  Collector collector(out);
  Reader reader(xml, collector);
  if (auto ok = reader.run(); !ok) return ok.error();
  if (out.declared_bodies && *out.declared_bodies != out.bodies.size()) {
    return parse_error(0, "<Bodies> says " + std::to_string(*out.declared_bodies) + " but " +
                              std::to_string(out.bodies.size()) + " <Body> elements follow");
  }
  return out;
}

std::string encode_parameters(std::span<const std::string> names, int minor,
                              ParametersRequest sections, double frequency_hz) {
  const std::string root = "QTM_Parameters_Ver_1." + std::to_string(minor);
  std::string x = "<" + root + ">\n";
  const bool new_format = minor >= kNewXmlFromMinor;
  if (sections.general) {
    char hz[32];
    const auto [end, ec] = std::to_chars(hz, hz + sizeof hz, frequency_hz);
    x += "  <General>\n    <Frequency>" + std::string(hz, ec == std::errc{} ? end : hz) +
         "</Frequency>\n";
    if (new_format) x += "    <EulerAngles First=\"Roll\" Second=\"Pitch\" Third=\"Yaw\"/>\n";
    x += "  </General>\n";
  }
  if (sections.six_d) {
    x += "  <The_6D>\n";
    if (!new_format) x += "    <Bodies>" + std::to_string(names.size()) + "</Bodies>\n";
    for (const auto& name : names) {
      x += "    <Body>\n      <Name>" + escape(name) + "</Name>\n";
      if (new_format) {
        if (minor >= 24) x += "      <Enabled>true</Enabled>\n";
        // Every element QTM writes for a body from 1.21 on (the Qualisys C++ SDK refuses a body
        // without BoneLengthTolerance, Filter or Data_orientation), minus the optional Mesh.
        x += "      <Color R=\"0\" G=\"255\" B=\"0\"/>\n"
             "      <MaximumResidual>10.000000</MaximumResidual>\n"
             "      <MinimumMarkersInBody>3</MinimumMarkersInBody>\n"
             "      <BoneLengthTolerance>10.000000</BoneLengthTolerance>\n"
             "      <Filter Preset=\"No filter\"/>\n"
             "      <Points/>\n"
             "      <Data_origin X=\"0.000000\" Y=\"0.000000\" Z=\"0.000000\" "
             "Relative_body=\"1\">0</Data_origin>\n"
             "      <Data_orientation R11=\"1.000000\" R12=\"0.000000\" R13=\"0.000000\" "
             "R21=\"0.000000\" R22=\"1.000000\" R23=\"0.000000\" R31=\"0.000000\" "
             "R32=\"0.000000\" R33=\"1.000000\" Relative_body=\"1\">0</Data_orientation>\n";
      } else {
        x += "      <RGBColor>ffffff</RGBColor>\n";
      }
      x += "    </Body>\n";
    }
    if (!new_format) {
      x += "    <Euler>\n      <First>Roll</First>\n      <Second>Pitch</Second>\n"
           "      <Third>Yaw</Third>\n    </Euler>\n";
    }
    x += "  </The_6D>\n";
  }
  return x + "</" + root + ">\n";
}

}  // namespace mocaplink::wire::qtm
