// Bounded files, YAML texts and names. See bounded_input.h.
#include "nonsmooth_sim/scene_io/bounded_input.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <yaml-cpp/eventhandler.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace nonsmooth_sim::scene_io {
namespace {

// "a FIFO", "a character device", ... for a file that is not a regular one.
const char* KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Where a document begins: all the event parser is asked for when the documents are counted.
class DocumentStart final : public YAML::EventHandler {
 public:
  YAML::Mark mark;

  void OnDocumentStart(const YAML::Mark& at) override { mark = at; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

[[noreturn]] void Refuse(const std::string& reason) { throw std::invalid_argument(reason); }

std::string Allowed(std::size_t max_bytes, const char* expected) {
  return std::string("allowed: ") + expected + ", a regular file of at most " +
         DescribeBytes(max_bytes);
}

// Closes a file descriptor on every path out.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

std::string DescribeBytes(std::size_t bytes) {
  std::string text = std::to_string(bytes) + " bytes";
  if (bytes >= (std::size_t{1} << 20) && bytes % (std::size_t{1} << 20) == 0) {
    text += " (" + std::to_string(bytes >> 20) + " MiB)";
  }
  return text;
}

std::string ReadBoundedFile(const std::string& path, std::size_t max_bytes,
                            const char* expected) {
  // the type first, from the name: a FIFO is never opened for a wait, a device never read
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    if (errno == ENOENT || errno == ENOTDIR) Refuse("no such file");
    Refuse(std::string("cannot be read (") + std::strerror(errno) + ")");
  }
  if (S_ISDIR(info.st_mode)) Refuse(std::string("is a directory, expected ") + expected);
  if (!S_ISREG(info.st_mode)) {
    Refuse(std::string("is ") + KindOf(info.st_mode) + ", not a regular file; " +
           Allowed(max_bytes, expected));
  }
  if (static_cast<unsigned long long>(info.st_size) > max_bytes) {
    Refuse("has " + std::to_string(info.st_size) + " bytes, more than the bound of " +
           DescribeBytes(max_bytes) + "; " + Allowed(max_bytes, expected));
  }
  // non-blocking: if the name was replaced by a FIFO meanwhile, the open does not wait
  const Descriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (fd.get() < 0) Refuse("cannot be opened (permissions?)");
  if (::fstat(fd.get(), &info) != 0 || !S_ISREG(info.st_mode)) {
    Refuse(std::string("is ") + KindOf(info.st_mode) + ", not a regular file; " +
           Allowed(max_bytes, expected));
  }
  // read at most max_bytes + 1: a file that grew since the stat is refused, not read whole
  std::string text;
  text.resize(std::min<std::size_t>(static_cast<std::size_t>(info.st_size), max_bytes) + 1);
  std::size_t size = 0;
  for (;;) {
    if (size == text.size()) {
      if (size > max_bytes) break;
      text.resize(std::min(max_bytes + 1, 2 * size + 4096));
    }
    const ssize_t n = ::read(fd.get(), &text[size], text.size() - size);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) Refuse(std::string("cannot be read (") + std::strerror(errno) + ")");
    if (n == 0) break;
    size += static_cast<std::size_t>(n);
  }
  if (size > max_bytes) {
    Refuse("has more than " + DescribeBytes(max_bytes) + " (it grew while read); " +
           Allowed(max_bytes, expected));
  }
  text.resize(size);
  return text;
}

void CheckYamlText(std::string_view text, std::size_t max_bytes) {
  if (text.size() > max_bytes) {
    Refuse("has " + std::to_string(text.size()) + " bytes, more than the bound of " +
           DescribeBytes(max_bytes));
  }
  const auto too_deep = [](int line) {
    Refuse("nested deeper than " + std::to_string(kMaxYamlDepth) + " levels (line " +
           std::to_string(line) + "; the bound on YAML nesting, counted over [ { and indentation)");
  };
  std::vector<std::size_t> indents;  // block levels: their indentation
  int flow = 0;                      // open [ { brackets
  int block = 0;                     // block depth where the current flow collection began
  char quote = 0;                    // inside a quoted scalar: its quote
  int line = 0;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view row = text.substr(start, end - start);
    ++line;
    std::size_t pos = 0;
    if (flow == 0 && quote == 0) {
      while (pos < row.size() && row[pos] == ' ') ++pos;
      const bool blank = pos == row.size() || row[pos] == '#' || row[pos] == '\r';
      if (!blank) {
        while (!indents.empty() && indents.back() > pos) indents.pop_back();
        if (indents.empty() || indents.back() < pos) indents.push_back(pos);
        block = static_cast<int>(indents.size());
        // compact nested block collections on one line: "- - - x", "? - x"
        while (pos < row.size() && (row[pos] == '-' || row[pos] == '?') &&
               (pos + 1 == row.size() || row[pos + 1] == ' ')) {
          ++block;
          pos += 1;
          while (pos < row.size() && row[pos] == ' ') ++pos;
        }
        if (block > kMaxYamlDepth) too_deep(line);
      }
    }
    char previous = 0;  // the last non-space character outside scalars on this line
    for (; pos < row.size(); ++pos) {
      const char c = row[pos];
      if (quote != 0) {
        if (quote == '"' && c == '\\') {
          ++pos;
        } else if (c == quote) {
          quote = 0;
        }
        continue;
      }
      if (c == '#' && (pos == 0 || row[pos - 1] == ' ' || row[pos - 1] == '\t')) break;
      if ((c == '"' || c == '\'') && (flow > 0 || previous == 0 || previous == ':' ||
                                      previous == '-' || previous == '?')) {
        quote = c;
      } else if ((c == '[' || c == '{') &&
                 (flow > 0 || previous == 0 || previous == ':' || previous == '-' ||
                  previous == '?')) {
        ++flow;
        if (block + flow > kMaxYamlDepth) too_deep(line);
      } else if ((c == ']' || c == '}') && flow > 0) {
        --flow;
      }
      if (c != ' ' && c != '\t') previous = c;
    }
    start = end + 1;
  }
}

YAML::Node LoadOneYamlDocument(const std::string& text, std::size_t max_bytes) {
  CheckYamlText(text, max_bytes);
  try {
    std::istringstream in(text);
    YAML::Parser parser(in);
    DocumentStart first;
    if (!parser.HandleNextDocument(first)) return YAML::Node();
    DocumentStart second;
    if (parser.HandleNextDocument(second)) {
      throw YamlTextError(second.mark.line + 1, second.mark.column + 1,
                          "a second YAML document (after --- or ..., or a token outside the "
                          "first, such as a \",\" outside brackets); allowed: one");
    }
    // parsed again into a tree: yaml-cpp's tree builder is not part of its public interface
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw YamlTextError(e.mark.line + 1, e.mark.column + 1, "not valid YAML: " + e.msg);
  }
}

void CheckNameLength(const std::string& what, std::string_view name) {
  if (name.size() <= kMaxNameLength) return;
  Refuse(what + " \"" + std::string(name.substr(0, 32)) + "...\": " +
         std::to_string(name.size()) + " bytes, more than the bound of " +
         std::to_string(kMaxNameLength) + " bytes for a name");
}

}  // namespace nonsmooth_sim::scene_io
