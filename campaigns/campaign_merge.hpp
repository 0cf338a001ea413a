#pragma once

#include <filesystem>
#include <vector>

namespace thetad {

// Combines the databases of the shards k/N of one campaign (the folders `shards`, each holding a
// campaign.sqlite written with --shard) into out/campaign.sqlite, as one run of the whole campaign
// would have written it. Refuses, naming the folders: shards of different campaigns (the SHA-256 of
// their campaign files differ), a shard given twice or missing, different N, an unfinished shard.
// The merged database is written under a temporary name and renamed when complete.
void merge_shards(const std::vector<std::filesystem::path>& shards, const std::filesystem::path& out);

}  // namespace thetad
