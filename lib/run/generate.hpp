#pragma once
// gen-primary, copy-settle and compact (SPEC §9, thesis §3.3) as library calls; the tools only
// parse options. Each prints a short report of what it did.
#include <string>

namespace dem {

struct GenerateOptions {
  std::string scene;
  std::string in;   // input checkpoint (copy-settle, compact)
  std::string out;  // output checkpoint
  std::string sizes;  // gen-primary: CSV of the size distribution asked and drawn; empty: none
  bool quiet = false;
};

void gen_primary(const GenerateOptions& o);
void copy_settle(const GenerateOptions& o);
void compact(const GenerateOptions& o);

}  // namespace dem
