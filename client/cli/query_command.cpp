#include "client/cli/query_command.h"

#include <cstdio>
#include <string>

#include "client/cli/cli_args.h"
#include "client/cli/progress_bar.h"
#include "client/cli/query_args.h"
#include "client/cli/quiet.h"
#include "client/cli/remote_options.h"
#include "client/cli/row_printer.h"
#include "core/io/write_file_bytes.h"
#include "proto/text/query_columns.h"
#include "proto/text/query_plot.h"
#include "render/plot_picture.h"

namespace soiq::cli {

namespace {

// `shown`: the positions of the row's values to print (QueryColumns::value_at).
std::vector<Cell> row_cells(const soiq::v1::QueryRow& row, const std::vector<size_t>& shown, bool csv) {
  const soiq::v1::Structure& s = row.structure();
  std::vector<Cell> cells = {int_cell(s.id()), text_cell(s.patient_id()), text_cell(s.study_uid()), text_cell(s.name()),
                             text_cell(s.laterality())};
  for (const size_t c : shown) {
    if (c < size_t(row.values_size())) {
      const auto& v = row.values(int(c)).value();
      cells.push_back(numbers_cell({v.begin(), v.end()}, csv));
    } else {
      cells.push_back({"", "null"});
    }
  }
  return cells;
}

// The summary line, then one line per reason candidates were skipped (stage 2 could not answer for
// them), so a short or empty table never looks like "nothing matched" when it is not.
void print_summary(const soiq::v1::QuerySummary& s) {
  if (!quiet())
    std::fprintf(stderr,
                 "%lld candidates, %lld computed, %lld cache hits, %lld matched, %lld returned, %lld skipped; "
                 "stage 1 %.1f ms, stage 2 %.1f ms, total %.1f ms\n",
                 (long long)s.stage1_candidates(), (long long)s.computed(), (long long)s.cache_hits(),
                 (long long)s.matched(), (long long)s.returned(), (long long)s.failed(), s.stage1_ms(), s.stage2_ms(),
                 s.total_ms());
  for (const soiq::v1::QuerySkip& k : s.skipped()) {
    std::string ids;
    for (const int64_t id : k.structure_ids()) ids += (ids.empty() ? "" : ", ") + std::to_string(id);
    if (k.count() > k.structure_ids_size()) ids += ", ...";
    std::fprintf(stderr, "  %lld skipped: %s (structure%s %s)\n", (long long)k.count(), k.reason().c_str(),
                 k.count() == 1 ? "" : "s", ids.c_str());
  }
}

// The rows' plot into a.plot (nothing to do without --plot).
Status write_plot(const QueryArgs& a, const std::vector<soiq::v1::QueryRow>& rows) {
  SOIQ_ASSIGN_OR_RETURN(
      const std::vector<proto_text::PlotColumn> columns,
      proto_text::query_plot_columns(a.request, rows.size(), [&](size_t r, size_t k) -> std::optional<double> {
        if (k >= size_t(rows[r].values_size())) return std::nullopt;
        const auto& v = rows[r].values(int(k)).value();
        if (v.size() != 1) return std::nullopt;
        return v[0];
      }));
  std::vector<render::PlotAxis> axes;
  for (const proto_text::PlotColumn& c : columns) axes.push_back({c.name, c.unit, c.values});
  render::PictureOptions picture;
  SOIQ_ASSIGN_OR_RETURN(picture.format, render::picture_format_of_path(a.plot));
  SOIQ_ASSIGN_OR_RETURN(const std::string bytes, render::plot_picture(axes, "", 720, 480, picture));
  return write_file_bytes(a.plot, bytes, "the plot");
}

// The number of candidates skipped: a partial answer when > 0.
Result<int64_t> query(const QueryArgs& a, const client::ClientOptions& remote) {
  SOIQ_ASSIGN_OR_RETURN(const client::Client c, connect(remote));
  const proto_text::QueryColumns columns = proto_text::query_columns(a.request);
  const std::vector<size_t>& shown = columns.value_at;
  RowPrinter out(a.format, columns.header);
  ProgressBar bar;
  client::QueryHandlers handlers;
  handlers.on_progress = [&](const soiq::v1::QueryProgress& p) {
    bar.update(p.stage(), p.done(), p.total());
    return true;
  };
  std::vector<soiq::v1::QueryRow> plotted;  // kept only for --plot
  handlers.on_row = [&](const soiq::v1::QueryRow& row) {
    out.row(row_cells(row, shown, a.format == "csv"));
    if (!a.plot.empty()) plotted.push_back(row);
    return true;
  };
  const Result<soiq::v1::QuerySummary> summary = c.query(a.request, handlers);
  bar.clear();
  if (!summary.ok() && interrupted()) {
    out.end();
    return interrupted_by_user("the rows printed are part of the answer only");
  }
  if (!summary.ok()) return in_command_line_words(summary.status(), a.request);
  out.end();
  print_summary(*summary);
  if (!a.plot.empty()) {
    SOIQ_RETURN_IF_ERROR(make_output_folder(a.plot));
    SOIQ_RETURN_IF_ERROR(write_plot(a, plotted));
    if (!quiet()) std::fprintf(stderr, "plot of %zu rows -> %s\n", plotted.size(), a.plot.c_str());
  }
  return summary->failed();
}

}  // namespace

int run_query_command(int argc, char** argv, const client::ClientOptions& remote) {
  int64_t skipped = 0;
  const int code = run_long_command("query", parse_query_args(argc, argv), remote,
                                    [&](const QueryArgs& a, const client::ClientOptions& options) -> Status {
                                      SOIQ_ASSIGN_OR_RETURN(skipped, query(a, options));
                                      return ok_status();
                                    });
  return code == 0 && skipped > 0 ? kExitPartial : code;
}

}  // namespace soiq::cli
