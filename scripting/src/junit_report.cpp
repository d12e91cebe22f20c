#include "graspkit/lua/junit_report.hpp"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <cstring>

#include "graspkit/base/error.hpp"
#include "graspkit/base/output_file.hpp"

namespace graspkit::lua {
namespace {

namespace fs = std::filesystem;

// The length of the well-formed UTF-8 sequence at text[i] (0 when it is not one).
std::size_t utf8Length(const std::string& text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = 0;
  unsigned int code = 0;
  if (lead < 0x80) return 1;
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
    code = lead & 0x1F;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    code = lead & 0x0F;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    code = lead & 0x07;
  } else {
    return 0;
  }
  if (i + length > text.size()) return 0;
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (byte(i + k) & 0x3F);
  }
  const bool overlong = (length == 3 && code < 0x800) || (length == 4 && code < 0x10000);
  const bool surrogate = code >= 0xD800 && code <= 0xDFFF;
  return overlong || surrogate || code > 0x10FFFF ? 0 : length;
}

// Test output is arbitrary bytes (a Lua string may hold anything); XML 1.0 allows only
// well-formed UTF-8 without most control characters. Each byte that breaks this becomes U+FFFD.
std::string xmlText(const std::string& text) {
  std::string clean;
  clean.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t length = utf8Length(text, i);
    if (length == 0 || (c < 0x20 && c != '\t' && c != '\n' && c != '\r')) {
      clean += "\xEF\xBF\xBD";
      ++i;
    } else {
      clean.append(text, i, length);
      i += length;
    }
  }
  return clean;
}

std::string seconds(double value) {
  return fmt::format("{:.3f}", value);
}

int countIn(const TestFileResult& file, TestStatus status) {
  int n = 0;
  for (const TestResult& test : file.tests) n += test.status == status ? 1 : 0;
  return n;
}

double secondsIn(const TestFileResult& file) {
  double sum = 0;
  for (const TestResult& test : file.tests) sum += test.seconds;
  return sum;
}

void setCounts(tinyxml2::XMLElement* element, int tests, int failures, int skipped, double time) {
  element->SetAttribute("tests", tests);
  element->SetAttribute("failures", failures);
  element->SetAttribute("errors", 0);  // errors in tests are failures too
  element->SetAttribute("skipped", skipped);
  element->SetAttribute("time", seconds(time).c_str());
}

tinyxml2::XMLElement* testCase(tinyxml2::XMLDocument& document, const std::string& file,
                               const TestResult& test) {
  tinyxml2::XMLElement* element = document.NewElement("testcase");
  element->SetAttribute("classname", xmlText(file).c_str());
  element->SetAttribute("name", xmlText(test.name).c_str());
  element->SetAttribute("time", seconds(test.seconds).c_str());
  if (test.status == TestStatus::Failed) {
    tinyxml2::XMLElement* failure = element->InsertNewChildElement("failure");
    const TestFailure& first = test.failures.front();
    // The first failure without a traceback: a one-line summary.
    const std::string message =
        first.kind == TestFailure::Kind::Expectation ? first.text() : first.message;
    failure->SetAttribute("message", xmlText(message).c_str());
    failure->SetAttribute("type",
                          first.kind == TestFailure::Kind::Expectation ? "expectation" : "error");
    std::string text;
    for (const TestFailure& each : test.failures) text += each.text() + "\n";
    failure->SetText(xmlText(text).c_str());
  } else if (test.status == TestStatus::Skipped) {
    tinyxml2::XMLElement* skipped = element->InsertNewChildElement("skipped");
    if (!test.skipReason.empty())
      skipped->SetAttribute("message", xmlText(test.skipReason).c_str());
  }
  return element;
}

}  // namespace

std::string junitReport(const TestReport& report) {
  tinyxml2::XMLDocument document;
  document.InsertEndChild(document.NewDeclaration());
  tinyxml2::XMLElement* suites = document.NewElement("testsuites");
  document.InsertEndChild(suites);
  suites->SetAttribute("name", "graspkit test");
  setCounts(suites, report.total(), report.count(TestStatus::Failed),
            report.count(TestStatus::Skipped), report.seconds());
  for (const TestFileResult& file : report.files) {
    tinyxml2::XMLElement* suite = suites->InsertNewChildElement("testsuite");
    suite->SetAttribute("name", xmlText(file.file).c_str());
    setCounts(suite, static_cast<int>(file.tests.size()), countIn(file, TestStatus::Failed),
              countIn(file, TestStatus::Skipped), secondsIn(file));
    for (const TestResult& test : file.tests)
      suite->InsertEndChild(testCase(document, file.file, test));
  }
  tinyxml2::XMLPrinter printer;
  document.Print(&printer);
  return printer.CStr();
}

void writeJunitReport(const TestReport& report, const fs::path& file) {
  try {
    writeFileAtomically(file, junitReport(report));
  } catch (const Error& e) {
    throw Error(SourceLocation{file.string()}, "cannot write the JUnit report: " + e.message());
  }
}

}  // namespace graspkit::lua
