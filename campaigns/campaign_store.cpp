#include "campaigns/campaign_store.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace thetad {

namespace {

namespace fs = std::filesystem;

// The database format: a reader checks it before trusting the columns.
constexpr const char* kFormat = "thetad-campaign-1";
// meta format_version (docs/glossary.md); absent in version 1. 2: J_dev (metric cost_dev) and the
// information set (column information) of every run. 3: the factors course and actuator_limits.
// 4: the factors turbulence_model, turbulence_intensity, turbulence_scale, servo_delay and
// servo_time_constant. 5: docs/glossary.md's names: the label in column label (was controller),
// the registered name in column controller, meta labels (was controllers), the units last in the
// factor and metric columns (duration_s, max_axis_error_m, rms_command_T_mr_N, wall_time_s, ...).
// 6: the factor slowdown and the flight computer's metrics missed_deadlines, longest_missed_run and
// skipped_samples (NULL without it, docs/model.md §15.7). 7: a column for each member of a factor
// family that the campaign names (plant.epsilon, initial_state.0: docs/campaigns.md), after the
// metrics.
// The report (scripts/campaign_report.py) reads versions 2 to 7; resume and merge only 7.
constexpr int kFormatVersion = 7;

// A prepared statement, finalized with its scope.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& sql) : db_(db) {
    if (sqlite3_prepare_v2(db, sql.c_str(), -1, &statement_, nullptr) != SQLITE_OK)
      throw Error(std::string("SQLite: ") + sqlite3_errmsg(db) + " in: " + sql);
  }
  ~Statement() { sqlite3_finalize(statement_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  void bind(int i, std::int64_t value) { check(sqlite3_bind_int64(statement_, i, value)); }
  void bind(int i, double value) { check(sqlite3_bind_double(statement_, i, value)); }
  void bind(int i, const std::string& value) {
    check(sqlite3_bind_text(statement_, i, value.c_str(), static_cast<int>(value.size()), SQLITE_TRANSIENT));
  }
  void bind_null(int i) { check(sqlite3_bind_null(statement_, i)); }
  // true while there is a row.
  bool step() {
    const int status = sqlite3_step(statement_);
    if (status == SQLITE_ROW) return true;
    if (status != SQLITE_DONE) throw Error(std::string("SQLite: ") + sqlite3_errmsg(db_));
    return false;
  }
  void reset() {
    sqlite3_reset(statement_);
    sqlite3_clear_bindings(statement_);
  }
  std::int64_t integer(int i) const { return sqlite3_column_int64(statement_, i); }
  double number(int i) const { return sqlite3_column_double(statement_, i); }
  bool is_null(int i) const { return sqlite3_column_type(statement_, i) == SQLITE_NULL; }
  std::string text(int i) const {
    const auto* value = sqlite3_column_text(statement_, i);
    return value ? reinterpret_cast<const char*>(value) : "";
  }

 private:
  void check(int status) const {
    if (status != SQLITE_OK) throw Error(std::string("SQLite: ") + sqlite3_errmsg(db_));
  }
  sqlite3* db_;
  sqlite3_stmt* statement_ = nullptr;
};

sqlite3* open_database(const fs::path& file, int flags) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(file.c_str(), &db, flags, nullptr) != SQLITE_OK) {
    const std::string message = db ? sqlite3_errmsg(db) : "out of memory";
    sqlite3_close(db);
    throw Error(file.string() + ": cannot open the campaign database: " + message);
  }
  sqlite3_busy_timeout(db, 10000);
  return db;
}

// A column's name in SQL: the family members' have a dot ("plant.epsilon").
std::string quoted(const std::string& column) { return '"' + column + '"'; }

// The runs table's columns after run_index: inputs, then outcome, then metric_columns(), then the
// members of factor families that the campaign names (`family_columns`).
std::vector<std::string> run_columns(const std::vector<std::string>& family_columns) {
  std::vector<std::string> columns{"cell", "draw", "scenario", "label", "controller", "seed"};
  for (const Factor& factor : factors()) columns.emplace_back(factor.name);
  for (const char* name : {"status", "reason", "information", "end_time_s", "controller_samples"})
    columns.emplace_back(name);
  for (const MetricColumn& metric : metric_columns()) columns.emplace_back(metric.name);
  for (const std::string& name : family_columns) columns.push_back(quoted(name));
  return columns;
}

// The family members the cells name, in the order they first appear.
std::vector<std::string> family_columns(const Campaign& campaign) {
  std::vector<std::string> names;
  for (const FactorValues& cell : campaign.cells) {
    for (const auto& [name, value] : cell) {
      const Factor* factor = find_factor(name);
      if (factor && factor->is_family() && std::find(names.begin(), names.end(), name) == names.end())
        names.push_back(name);
    }
  }
  return names;
}

}  // namespace

fs::path store_file(const fs::path& out) { return out / "campaign.sqlite"; }

void CampaignStore::check_format(const fs::path& file) {
  if (meta("format") != kFormat) throw Error(file.string() + ": not a thetad campaign database (" + kFormat + ")");
  const std::string version = meta("format_version");
  version_ = 1;
  if (!version.empty()) {
    std::size_t end = 0;
    try {
      version_ = std::stoi(version, &end);
    } catch (const std::logic_error&) {
      end = 0;
    }
    if (end == 0 || end != version.size())
      throw Error(file.string() + ": meta format_version '" + version + "' is not a whole number");
  }
  if (version_ > kFormatVersion)
    throw Error(file.string() + ": written by a newer thetad (format_version " + version + "; this one reads up to " +
                std::to_string(kFormatVersion) + ")");
}

void CampaignStore::require_current_format(const std::string& refused) const {
  if (version_ == kFormatVersion) return;
  throw Error(file_.string() + ": a campaign database of format_version " + std::to_string(version_) +
              ", written by an earlier thetad (this one writes version " + std::to_string(kFormatVersion) +
              ", with docs/glossary.md's column names): " + refused + "; `thetad campaign report` still reads it, "
              "or run the campaign anew into another folder");
}

CampaignStore::CampaignStore(const fs::path& file, const Campaign& campaign, const Shard& shard, Open open,
                             const std::string& provenance)
    : file_(file) {
  const bool exists = fs::exists(file);
  if (open == Open::create && exists)
    throw Error(file.string() + " exists: pass --resume to continue that campaign, or choose another --out");
  if (open == Open::resume && !exists) throw Error(file.string() + ": nothing to resume (no such database)");
  db_ = open_database(file, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
  make_durable();
  if (open == Open::create) {
    version_ = kFormatVersion;
    family_columns_ = family_columns(campaign);
    create_schema(campaign, shard, provenance);
    sync_entry(file);
    return;
  }
  check_format(file);
  require_current_format("cannot resume it");
  if (meta("campaign_sha256") != campaign.sha256)
    throw Error(file.string() + ": holds another campaign (its campaign file's SHA-256 differs from " +
                campaign.file.string() + "'s): refusing to resume");
  if (meta("shard") != shard.text())
    throw Error(file.string() + ": holds shard " + meta("shard") + ", not " + shard.text() + ": refusing to resume");
  read_family_columns();
}

CampaignStore::CampaignStore(const fs::path& file) : file_(file) {
  if (!fs::exists(file)) throw Error(file.string() + ": no such campaign database");
  db_ = open_database(file, SQLITE_OPEN_READONLY);
  check_format(file);
  read_family_columns();
}

CampaignStore::CampaignStore(const fs::path& file, const CampaignStore& like)
    : file_(file), version_(kFormatVersion), family_columns_(like.family_columns_) {
  if (fs::exists(file)) throw Error(file.string() + " exists: refusing to overwrite it");
  db_ = open_database(file, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE);
  make_durable();
  execute("BEGIN");
  create_tables();
  Statement select(like.db_, "SELECT key, value FROM meta ORDER BY key");
  while (select.step()) set_meta(select.text(0), select.text(1));
  set_meta("shard", Shard{}.text());
  execute("COMMIT");
  sync_entry(file);
}

void CampaignStore::make_durable() {
  // WAL: readers (pandas read_sql, `campaign report`) may look while the campaign runs. FULL: the
  // log is flushed to disk (fsync) at every commit, so a run the progress counts as written
  // survives a power loss, not only a killed process (NORMAL would flush at checkpoints only and
  // may lose the last commits; either keeps the database whole). The cost is one fsync per batch
  // of runs: the writer commits what finished every 250 ms, under MPI as often as runs arrive
  // (docs/campaigns.md).
  execute("PRAGMA journal_mode=WAL");
  execute("PRAGMA synchronous=FULL");
}

CampaignStore::~CampaignStore() { sqlite3_close(db_); }

void CampaignStore::execute(const std::string& sql) const {
  char* message = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &message) != SQLITE_OK) {
    const std::string text = message ? message : "unknown error";
    sqlite3_free(message);
    throw Error(file_.string() + ": SQLite: " + text);
  }
}

void CampaignStore::read_family_columns() {
  Statement columns(db_, "SELECT name FROM pragma_table_info('runs')");
  while (columns.step()) {
    const Factor* factor = find_factor(columns.text(0));
    if (factor && factor->is_family()) family_columns_.push_back(columns.text(0));
  }
}

void CampaignStore::create_tables() {
  std::string sql = "CREATE TABLE meta (key TEXT PRIMARY KEY, value TEXT NOT NULL);"
                    " CREATE TABLE runs (run_index INTEGER PRIMARY KEY";
  for (const std::string& column : run_columns(family_columns_)) {
    const bool is_text = column == "scenario" || column == "label" || column == "controller" || column == "seed" ||
                         column == "status" || column == "reason" || column == "information";
    sql += ", " + column + (is_text ? " TEXT" : column == "cell" || column == "draw" || column == "controller_samples" ? " INTEGER" : " REAL");
  }
  sql += ");";
  execute(sql);
}

void CampaignStore::create_schema(const Campaign& campaign, const Shard& shard, const std::string& provenance) {
  execute("BEGIN");
  create_tables();
  nlohmann::ordered_json scenarios = nlohmann::ordered_json::array();
  for (const auto& scenario : campaign.scenarios) scenarios.push_back(scenario);
  nlohmann::ordered_json labels = nlohmann::ordered_json::array();
  for (const auto& spec : campaign.controllers) labels.push_back(spec.label);
  set_meta("format", kFormat);
  set_meta("format_version", std::to_string(kFormatVersion));
  set_meta("campaign_name", campaign.name);
  set_meta("campaign_file", fs::absolute(campaign.file).lexically_normal().string());
  set_meta("campaign_text", campaign.text);
  set_meta("campaign_sha256", campaign.sha256);
  set_meta("shard", shard.text());
  set_meta("run_count", std::to_string(campaign.run_count()));
  set_meta("draws", std::to_string(campaign.draws));
  set_meta("swept", nlohmann::json(campaign.swept).dump());
  set_meta("labels", labels.dump());
  set_meta("scenarios", scenarios.dump());
  set_meta("provenance", provenance);
  execute("COMMIT");
}

std::string CampaignStore::meta(const std::string& key) const {
  Statement select(db_, "SELECT value FROM meta WHERE key = ?");
  select.bind(1, key);
  return select.step() ? select.text(0) : std::string();
}

void CampaignStore::set_meta(const std::string& key, const std::string& value) {
  Statement insert(db_, "INSERT OR REPLACE INTO meta (key, value) VALUES (?, ?)");
  insert.bind(1, key);
  insert.bind(2, value);
  insert.step();
}

std::set<std::int64_t> CampaignStore::stored() const {
  Statement select(db_, "SELECT run_index FROM runs");
  std::set<std::int64_t> indices;
  while (select.step()) indices.insert(select.integer(0));
  return indices;
}

void CampaignStore::write(const std::vector<RunRecord>& records) {
  if (records.empty()) return;
  const std::vector<std::string> columns = run_columns(family_columns_);
  std::string sql = "INSERT INTO runs (run_index", values = "?";
  for (const auto& column : columns) {
    sql += ", " + column;
    values += ", ?";
  }
  sql += ") VALUES (" + values + ")";
  execute("BEGIN");
  try {
    Statement insert(db_, sql);
    for (const RunRecord& r : records) {
      int i = 1;
      insert.bind(i++, r.index);
      insert.bind(i++, static_cast<std::int64_t>(r.cell));
      insert.bind(i++, static_cast<std::int64_t>(r.draw));
      insert.bind(i++, r.scenario);
      insert.bind(i++, r.label);
      insert.bind(i++, r.controller);
      insert.bind(i++, std::to_string(r.seed));  // text: SQLite integers are signed 64-bit
      const auto bind_factor = [&](std::string_view name) {
        const auto given = std::find_if(r.factors.begin(), r.factors.end(),
                                        [&](const auto& value) { return value.first == name; });
        if (given == r.factors.end()) {
          insert.bind_null(i++);  // the scenario's own value
        } else {
          insert.bind(i++, given->second);
        }
      };
      for (const Factor& factor : factors()) bind_factor(factor.name);
      insert.bind(i++, r.status);
      insert.bind(i++, r.reason);
      insert.bind(i++, r.information);
      insert.bind(i++, r.end_time_s);
      insert.bind(i++, r.controller_samples);
      for (double value : r.metrics) insert.bind(i++, value);
      for (const std::string& name : family_columns_) bind_factor(name);
      insert.step();
      insert.reset();
    }
    execute("COMMIT");
  } catch (...) {
    execute("ROLLBACK");
    throw;
  }
}

std::vector<RunRecord> CampaignStore::records() const {
  require_current_format("cannot read its runs to merge or compare them");
  const std::vector<std::string> columns = run_columns(family_columns_);
  std::string sql = "SELECT run_index";
  for (const auto& column : columns) sql += ", " + column;
  sql += " FROM runs ORDER BY run_index";
  Statement select(db_, sql);
  std::vector<RunRecord> records;
  while (select.step()) {
    RunRecord r;
    int i = 0;
    r.index = select.integer(i++);
    r.cell = static_cast<int>(select.integer(i++));
    r.draw = static_cast<int>(select.integer(i++));
    r.scenario = select.text(i++);
    r.label = select.text(i++);
    r.controller = select.text(i++);
    r.seed = std::stoull(select.text(i++));
    for (const Factor& factor : factors()) {
      if (!select.is_null(i)) r.factors.emplace_back(std::string(factor.name), select.number(i));
      ++i;
    }
    r.status = select.text(i++);
    r.reason = select.text(i++);
    r.information = select.text(i++);
    r.end_time_s = select.number(i++);
    r.controller_samples = select.integer(i++);
    // A metric a run does not have (J_dev of a plant without trims) is stored as NULL.
    for (std::size_t m = 0; m < metric_columns().size(); ++m, ++i)
      r.metrics.push_back(select.is_null(i) ? std::numeric_limits<double>::quiet_NaN() : select.number(i));
    for (const std::string& name : family_columns_) {
      if (!select.is_null(i)) r.factors.emplace_back(name, select.number(i));
      ++i;
    }
    records.push_back(std::move(r));
  }
  return records;
}

}  // namespace thetad
