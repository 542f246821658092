#include "OpenMeshSkinned/IO/ReaderLog.hh"

#include <assimp/DefaultLogger.hpp>
#include <assimp/LogStream.hpp>

#include <algorithm>
#include <cctype>

namespace OpenMeshSkinned {

struct ReaderLog::Sink {
  std::vector<std::pair<std::string, size_t>> messages;
  size_t more = 0;  // data-loss messages beyond kMaxDistinct distinct ones
};

namespace {

class Stream : public Assimp::LogStream {
public:
  explicit Stream(std::shared_ptr<ReaderLog::Sink> sink) : sink_(std::move(sink)) {}
  void write(const char* message) override;

private:
  std::shared_ptr<ReaderLog::Sink> sink_;
};

// "Warn,  T0: Some faces had out-of-range indices. Those faces were dropped.\n" -> the sentence.
std::string strip(std::string m) {
  const size_t colon = m.find(": ");
  if (colon != std::string::npos && colon < 16) m.erase(0, colon + 2);
  while (!m.empty() && std::isspace(static_cast<unsigned char>(m.back()))) m.pop_back();
  return m;
}

}  // namespace

bool ReaderLog::reports_data_loss(const std::string& message) {
  std::string m = message;
  std::transform(m.begin(), m.end(), m.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const char* word : {"dropped", "dropping", "skipp", "ignor", "discard", "out of range", "out-of-range"})
    if (m.find(word) != std::string::npos) return true;
  return false;
}

void Stream::write(const char* message) {
  const std::string m = strip(message);
  if (!ReaderLog::reports_data_loss(m)) return;
  auto& list = sink_->messages;
  auto it = std::find_if(list.begin(), list.end(), [&](const auto& e) { return e.first == m; });
  if (it != list.end())
    ++it->second;
  else if (list.size() < ReaderLog::kMaxDistinct)
    list.emplace_back(m, 1);
  else
    ++sink_->more;  // a corrupt file can make a reader log millions of distinct lines: keep the cost flat
}

ReaderLog::ReaderLog() : sink_(std::make_shared<Sink>()) {
  Assimp::DefaultLogger::create("", Assimp::Logger::NORMAL, 0);
  Assimp::DefaultLogger::get()->attachStream(new Stream(sink_), Assimp::Logger::Warn | Assimp::Logger::Err);
}

ReaderLog::~ReaderLog() { Assimp::DefaultLogger::kill(); }

std::vector<std::string> ReaderLog::data_loss() const {
  std::vector<std::string> out;
  for (const auto& [m, n] : sink_->messages) out.push_back(n > 1 ? m + " (" + std::to_string(n) + " times)" : m);
  if (sink_->more > 0) out.push_back("and " + std::to_string(sink_->more) + " more such messages");
  return out;
}

}  // namespace OpenMeshSkinned
