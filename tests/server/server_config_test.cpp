// soiqd's configuration on its own: defaults, flags over environment variables, and a refusal
// naming the flag or variable for every bad value.
#include "server/app/server_config.h"

#include <gtest/gtest.h>

#include <cctype>
#include <map>
#include <string>
#include <vector>

namespace soiq::server {
namespace {

struct Parsed {
  Result<ServerConfig> config;
  bool help = false;
};

Parsed parse(std::vector<std::string> args, std::map<std::string, std::string> env = {}) {
  args.insert(args.begin(), "soiqd");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  Parsed p{Status(StatusCode::kInternal, "not parsed"), false};
  p.config = parse_server_config(int(argv.size()), argv.data(), p.help, [&](const char* name) -> const char* {
    auto it = env.find(name);
    return it == env.end() ? nullptr : it->second.c_str();
  });
  return p;
}

bool says(const Status& s, const std::string& part) { return s.message().find(part) != std::string::npos; }

TEST(ServerConfig, WithNothingGivenEveryValueIsTheDocumentedDefault) {
  Parsed p = parse({});
  ASSERT_TRUE(p.config.ok()) << p.config.status().to_string();
  EXPECT_EQ(p.config->listen, "127.0.0.1:50051");
  EXPECT_EQ(p.config->db_path, "var/soiq.db");
  EXPECT_EQ(p.config->max_upload_bytes, 256ll << 20);
  EXPECT_EQ(p.config->max_grid_voxels, 500'000'000);
  EXPECT_GT(p.config->memory_budget_bytes, 0);  // half the RAM, whatever this machine has
  EXPECT_GT(p.config->workers, 0);
  EXPECT_FALSE(p.config->pacs_peer);
  EXPECT_FALSE(p.help);
}

TEST(ServerConfig, AFlagWinsOverItsEnvironmentVariable) {
  Parsed p = parse({"--workers", "3"}, {{"SOIQ_WORKERS", "7"}, {"SOIQ_DB", "store/x.db"}});
  ASSERT_TRUE(p.config.ok()) << p.config.status().to_string();
  EXPECT_EQ(p.config->workers, 3);
  EXPECT_EQ(p.config->db_path, "store/x.db");
}

TEST(ServerConfig, TheMemoryBudgetTakesUnits) {
  Parsed p = parse({"--memory-budget", "512M"});
  ASSERT_TRUE(p.config.ok()) << p.config.status().to_string();
  EXPECT_EQ(p.config->memory_budget_bytes, 512ll << 20);
}

TEST(ServerConfig, APacsFlagGivesAPeerWithTheCallingAeAndTimeout) {
  Parsed p = parse({"--pacs", "ORTHANC@127.0.0.1:4242", "--pacs-calling-ae", "ME", "--pacs-timeout", "5"});
  ASSERT_TRUE(p.config.ok()) << p.config.status().to_string();
  ASSERT_TRUE(p.config->pacs_peer);
  EXPECT_EQ(p.config->pacs_peer->called_ae, "ORTHANC");
  EXPECT_EQ(p.config->pacs_peer->host, "127.0.0.1");
  EXPECT_EQ(p.config->pacs_peer->port, 4242);
  EXPECT_EQ(p.config->pacs_peer->calling_ae, "ME");
  EXPECT_EQ(p.config->pacs_peer->timeout_seconds, 5);
}

TEST(ServerConfig, AViewerUrlWithTheStudyIsKept) {
  Parsed p = parse({"--viewer-url", "http://127.0.0.1:3000/viewer?StudyInstanceUIDs={study}"});
  ASSERT_TRUE(p.config.ok()) << p.config.status().to_string();
  EXPECT_EQ(p.config->viewer_url, "http://127.0.0.1:3000/viewer?StudyInstanceUIDs={study}");
  EXPECT_EQ(parse({}).config->viewer_url, "");
}

TEST(ServerConfig, InstancesAreKeptAndNoOriginIsAllowedUnlessSaidOtherwise) {
  const Parsed defaults = parse({});
  EXPECT_TRUE(defaults.config->keep_instances);
  EXPECT_EQ(defaults.config->http_cors_origin, "");
  Parsed p = parse({"--keep-instances", "off", "--http-cors-origin", "http://127.0.0.1:3000"});
  ASSERT_TRUE(p.config.ok()) << p.config.status().to_string();
  EXPECT_FALSE(p.config->keep_instances);
  EXPECT_EQ(p.config->http_cors_origin, "http://127.0.0.1:3000");
  EXPECT_EQ(parse({}, {{"SOIQ_HTTP_CORS_ORIGIN", "*"}}).config->http_cors_origin, "*");
}

TEST(ServerConfig, EveryBadValueIsInvalidArgumentNamingWhereItCameFrom) {
  const std::vector<std::pair<Parsed, std::string>> cases = {
      {parse({"--workers", "0"}), "--workers"},
      {parse({"--workers", "many"}), "--workers"},
      {parse({}, {{"SOIQ_MAX_UPLOAD_BYTES", "-1"}}), "SOIQ_MAX_UPLOAD_BYTES"},
      {parse({"--tls-cert", "a.pem"}), "--tls-key"},
      {parse({"--pacs", "no-at-sign:4242"}), "--pacs"},
      {parse({"--frobnicate"}), "--frobnicate"},
      {parse({"--db"}), "--db"},
      {parse({"--http-port-file", "p"}), "--http"},
      {parse({"--keep-patient-names", "yes"}), "--keep-patient-names"},
      {parse({"--http-timeout", "0"}), "--http-timeout"},
      {parse({"--http-max-connections", "none"}), "--http-max-connections"},
      {parse({"--viewer-url", "ftp://viewer/{study}"}), "--viewer-url"},
      {parse({"--viewer-url", "http://viewer/without-the-study"}), "--viewer-url"},
      {parse({"--keep-instances", "sometimes"}), "--keep-instances"},
      {parse({"--http-cors-origin", "127.0.0.1:3000"}), "--http-cors-origin"},
      {parse({"--http-cors-origin", "http://127.0.0.1:3000/ohif"}), "--http-cors-origin"},
      {parse({"--http-cors-origin", "https://"}), "--http-cors-origin"},
  };
  for (const auto& [p, name] : cases) {
    EXPECT_EQ(p.config.status().code(), StatusCode::kInvalidArgument) << name;
    EXPECT_TRUE(says(p.config.status(), name)) << p.config.status().message();
  }
}

// --help and the parser cannot disagree: every flag the help describes is one the parser takes
// (each given an unparseable value must be refused for its value, not as unknown), in the
// environment variable the help names, and a mistyped flag gets the nearest real one.
TEST(ServerConfig, EveryFlagTheHelpDescribesIsParsedAndNamedWithItsVariable) {
  const std::string usage = server_usage();
  const std::vector<std::string> flags = server_option_flags();
  EXPECT_EQ(flags.size(), 27u);
  for (const std::string& flag : flags) {
    const Parsed p = parse({flag, ""});
    ASSERT_FALSE(p.config.ok()) << flag << " with an empty value";
    EXPECT_FALSE(says(p.config.status(), "unknown option")) << p.config.status().message();
    EXPECT_TRUE(says(p.config.status(), flag)) << p.config.status().message();
    std::string env = "SOIQ_" + flag.substr(2);
    for (char& c : env) c = c == '-' ? '_' : char(std::toupper(static_cast<unsigned char>(c)));
    EXPECT_NE(usage.find("environment: " + env + "\n"), std::string::npos) << env;
    const Parsed from_env = parse({}, {{env, ""}});
    EXPECT_FALSE(from_env.config.ok()) << env << " is not read";
  }
  const Parsed typo = parse({"--lisen", "127.0.0.1:0"});
  EXPECT_TRUE(says(typo.config.status(), "did you mean '--listen'?")) << typo.config.status().message();
}

TEST(ServerConfig, PrecomputeIsOnUnlessTurnedOffAndTakesOnlyOnWeightedOrOff) {
  EXPECT_TRUE(parse({}).config->precompute);
  EXPECT_FALSE(parse({"--precompute", "off"}).config->precompute);
  EXPECT_FALSE(parse({}, {{"SOIQ_PRECOMPUTE", "off"}}).config->precompute);
  EXPECT_TRUE(parse({"--precompute=on"}, {{"SOIQ_PRECOMPUTE", "off"}}).config->precompute);
  const Parsed bad = parse({"--precompute", "yes"});
  ASSERT_FALSE(bad.config.ok());
  EXPECT_TRUE(says(bad.config.status(), "--precompute must be on, weighted or off, got 'yes'"))
      << bad.config.status().message();
}

TEST(ServerConfig, WeightedPrecomputeIsOffUnlessAsked) {
  EXPECT_FALSE(parse({}).config->precompute_weighted);
  EXPECT_FALSE(parse({"--precompute", "on"}).config->precompute_weighted);
  const Parsed weighted = parse({"--precompute", "weighted"});
  ASSERT_TRUE(weighted.config.ok());
  EXPECT_TRUE(weighted.config->precompute);
  EXPECT_TRUE(weighted.config->precompute_weighted);
  EXPECT_TRUE(parse({}, {{"SOIQ_PRECOMPUTE", "weighted"}}).config->precompute_weighted);
  const Parsed off = parse({"--precompute=off"}, {{"SOIQ_PRECOMPUTE", "weighted"}});
  EXPECT_FALSE(off.config->precompute);
  EXPECT_FALSE(off.config->precompute_weighted);
}

TEST(ServerConfig, DicomwebIsOffAndNamesAreDroppedUnlessAsked) {
  Parsed p = parse({});
  ASSERT_TRUE(p.config.ok());
  EXPECT_EQ(p.config->http_listen, "");
  EXPECT_FALSE(p.config->keep_patient_names);
  p = parse({"--http", "127.0.0.1:0", "--http-port-file", "h.port"}, {{"SOIQ_KEEP_PATIENT_NAMES", "on"}});
  ASSERT_TRUE(p.config.ok()) << p.config.status().to_string();
  EXPECT_EQ(p.config->http_listen, "127.0.0.1:0");
  EXPECT_EQ(p.config->http_port_file, "h.port");
  EXPECT_TRUE(p.config->keep_patient_names);
}

TEST(ServerConfig, HelpIsReportedNotAnError) {
  Parsed p = parse({"--help"});
  EXPECT_TRUE(p.help);
  EXPECT_NE(std::string(server_usage()).find("--memory-budget"), std::string::npos);
}

}  // namespace
}  // namespace soiq::server
