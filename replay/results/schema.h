#pragma once
// The results store's tables and their migrations. Version N of the schema is the first N steps
// of kMigrations; a store records its version (SQLite PRAGMA user_version) and is brought up to
// date inside one write transaction when opened, so a store is always at one version or the next.
#include "results/database.h"

namespace aor::results {

// The version this aoreplay writes.
int currentSchemaVersion();

// Applies the missing migrations in one transaction holding the write lock. Throws InputError
// when the store is newer than this aoreplay (it refuses to write what it does not know).
void migrate(Database& db);

}  // namespace aor::results
