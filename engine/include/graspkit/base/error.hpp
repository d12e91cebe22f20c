#pragma once
// Errors for bad user input. Every error names where the input was wrong (file, line, element),
// so a message reads like a compiler diagnostic:
//   Barrett.xml:42: <joint>: <theta> expression 'd9+5' names dof 9, robot has 4

#include <stdexcept>
#include <string>

namespace graspkit {

// Where in the user's input a problem was found. `line` is 0 when unknown (e.g. a binary mesh),
// `element` is empty when the problem concerns the whole file.
struct SourceLocation {
  std::string file;
  int line = 0;
  std::string element;

  std::string str() const;  // "file:line: <element>" with the unknown parts left out
};

// Thrown for bad input: malformed files, missing files, out-of-range values, wrong units.
class Error : public std::runtime_error {
 public:
  Error(SourceLocation where, const std::string& message);
  explicit Error(const std::string& message) : Error(SourceLocation{}, message) {}

  const SourceLocation& where() const { return where_; }
  const std::string& message() const { return message_; }

 private:
  SourceLocation where_;
  std::string message_;
};

}  // namespace graspkit
