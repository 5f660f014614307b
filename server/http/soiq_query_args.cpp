#include "server/http/soiq_query_args.h"

#include "proto/text/query_options.h"

namespace soiq::server::http {

Result<v1::QueryRequest> parse_soiq_query_args(const std::vector<std::pair<std::string, std::string>>& args) {
  proto_text::QueryRequestBuilder request("");
  for (const auto& [name, value] : args) SOIQ_RETURN_IF_ERROR(request.add(name, value));
  return request.finish();
}

}  // namespace soiq::server::http
