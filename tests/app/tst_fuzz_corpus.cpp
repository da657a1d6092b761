// The fuzz corpora (tests/fuzz/corpus/<target>/) replayed through the fuzz targets'
// checks in the ordinary build, so every finding of docs/fuzzing.md stays fixed: a
// target aborts (the test crashes) when an input breaks its contract.
#include <QtTest>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "scan/scan_import.h"

extern "C" int fuzz_scenario_one(const std::uint8_t* data, std::size_t size);
extern "C" int fuzz_model_cache_one(const std::uint8_t* data, std::size_t size);
extern "C" int fuzz_protocol_one(const std::uint8_t* data, std::size_t size);
extern "C" int fuzz_recording_one(const std::uint8_t* data, std::size_t size);
extern "C" int fuzz_scan_import_one(const std::uint8_t* data, std::size_t size);

namespace {

int replay(const char* target, int (*one)(const std::uint8_t*, std::size_t)) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(PALPATION_FUZZ_CORPUS) / target;
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    std::ifstream in(e.path(), std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    one(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    ++n;
  }
  return n;
}

}  // namespace

class TestFuzzCorpus : public QObject {
  Q_OBJECT
 private slots:
  void scenario() { QVERIFY(replay("scenario", fuzz_scenario_one) >= 3); }
  void modelCache() { QVERIFY(replay("model_cache", fuzz_model_cache_one) >= 2); }
  void protocol() { QVERIFY(replay("protocol", fuzz_protocol_one) >= 3); }
  void recording() { QVERIFY(replay("recording", fuzz_recording_one) >= 1); }
  void scanImport() {
    if (!palpation::app::scan::scan_reader_available()) QSKIP("this build has no assimp (scan import)");
    QVERIFY(replay("scan_import", fuzz_scan_import_one) >= 5);
  }
};

QTEST_GUILESS_MAIN(TestFuzzCorpus)
#include "tst_fuzz_corpus.moc"
