#include "campaigns/campaign_merge.hpp"

#include <map>
#include <memory>

#include "campaigns/campaign_store.hpp"
#include "campaigns/run_plan.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace thetad {

namespace fs = std::filesystem;

void merge_shards(const std::vector<fs::path>& shards, const fs::path& out) {
  if (shards.empty()) throw Error("campaign merge: no shard folders given");
  std::map<int, std::unique_ptr<CampaignStore>> by_part;
  int parts = 0;
  std::int64_t run_count = 0;
  std::string sha256;
  fs::path first;
  for (const fs::path& folder : shards) {
    auto store = std::make_unique<CampaignStore>(store_file(folder));
    store->require_current_format("cannot merge it");
    const Shard shard = parse_shard(store->meta("shard"));
    if (first.empty()) {
      first = folder;
      sha256 = store->meta("campaign_sha256");
      parts = shard.n;
      run_count = std::stoll(store->meta("run_count"));
    } else if (store->meta("campaign_sha256") != sha256) {
      throw Error("campaign merge: " + folder.string() + " holds another campaign than " + first.string() + " ('" +
                  store->meta("campaign_name") + "': the SHA-256 of the campaign files differ)");
    } else if (shard.n != parts) {
      throw Error("campaign merge: " + folder.string() + " is shard " + shard.text() + ", " + first.string() +
                  " one of " + std::to_string(parts) + " shards");
    }
    if (by_part.contains(shard.k)) throw Error("campaign merge: shard " + shard.text() + " is given twice (" + folder.string() + ")");
    std::int64_t expected = 0;
    for (std::int64_t i = 0; i < run_count; ++i) expected += shard.holds(i) ? 1 : 0;
    const auto stored = static_cast<std::int64_t>(store->stored().size());
    if (stored != expected)
      throw Error("campaign merge: shard " + shard.text() + " in " + folder.string() + " is unfinished (" +
                  std::to_string(stored) + " of " + std::to_string(expected) + " runs): resume it first (--resume)");
    by_part[shard.k] = std::move(store);
  }
  for (int k = 1; k <= parts; ++k) {
    if (!by_part.contains(k))
      throw Error("campaign merge: shard " + std::to_string(k) + "/" + std::to_string(parts) + " is missing");
  }
  fs::create_directories(out);
  const fs::path file = store_file(out);
  if (fs::exists(file)) throw Error(file.string() + " exists: refusing to overwrite it");
  PartialFile partial(file);
  {
    CampaignStore merged(partial.path(), *by_part.begin()->second);
    for (const auto& [k, store] : by_part) merged.write(store->records());
  }
  partial.commit();
}

}  // namespace thetad
