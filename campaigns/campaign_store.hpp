#pragma once

#include <cstdint>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "campaigns/campaign.hpp"
#include "campaigns/run_plan.hpp"
#include "campaigns/run_record.hpp"

struct sqlite3;

namespace thetad {

// The SQLite database of one campaign (or one shard of it): a `runs` table (one row per run: every
// input factor, seed, status, the reason it did not complete and summary figure, keyed by the run index) and a
// `meta` table (the campaign file, its SHA-256, the shard, and the experiment library's provenance
// of each scenario's flights). Rows are committed in transactions as runs finish, so a killed campaign loses at most
// the runs in flight, and reopening with resume skips the runs already stored. One writer: the
// thread (or MPI rank 0) that owns this object.
class CampaignStore {
 public:
  enum class Open { create, resume };
  // Creates `file` (refusing an existing one) or resumes it (refusing a database of another
  // campaign or shard: the SHA-256 of the campaign file and the shard must match). `provenance`
  // (JSON) is stored on creation: what produced the runs (CampaignWorker::provenance()).
  CampaignStore(const std::filesystem::path& file, const Campaign& campaign, const Shard& shard, Open open,
                const std::string& provenance);
  // Opens an existing database to read (merge, report): of this format_version or an earlier one
  // (format_version() says which; records() reads only this one).
  explicit CampaignStore(const std::filesystem::path& file);
  // Creates `file` for the runs of `like`'s campaign as a whole (merge): its meta table, shard 1/1.
  CampaignStore(const std::filesystem::path& file, const CampaignStore& like);
  ~CampaignStore();
  CampaignStore(const CampaignStore&) = delete;
  CampaignStore& operator=(const CampaignStore&) = delete;

  // The run indices already stored.
  std::set<std::int64_t> stored() const;
  // Every stored record, by run index; throws for a database of an earlier format_version.
  std::vector<RunRecord> records() const;
  // Stores `records` in one transaction.
  void write(const std::vector<RunRecord>& records);

  // A value of the meta table ("" when absent).
  std::string meta(const std::string& key) const;
  void set_meta(const std::string& key, const std::string& value);

  const std::filesystem::path& file() const { return file_; }
  // meta format_version (1 when absent).
  int format_version() const { return version_; }
  // Throws thetad::Error, saying what is `refused` and what to do, unless the database is of the
  // format_version this thetad writes.
  void require_current_format(const std::string& refused) const;

 private:
  void execute(const std::string& sql) const;
  // WAL journal, every commit flushed to disk (synchronous=FULL).
  void make_durable();
  // Throws thetad::Error unless the database is a campaign database this thetad can read (not of a
  // newer format_version); sets version_.
  void check_format(const std::filesystem::path& file);
  // The runs table's columns of factor families' members (plant.epsilon), as the database has them.
  void read_family_columns();
  void create_tables();
  void create_schema(const Campaign& campaign, const Shard& shard, const std::string& provenance);

  std::filesystem::path file_;
  sqlite3* db_ = nullptr;
  int version_ = 0;
  std::vector<std::string> family_columns_;  // the members of factor families the campaign names
};

// The database file of a campaign's output folder.
std::filesystem::path store_file(const std::filesystem::path& out);

}  // namespace thetad
