#pragma once
// `soiq features ID [--features LIST] [--region inside|shell:R|core:R]... [--image MODALITY|UID]...
//  [--spacing S|SX,SY,SZ [--margin N] | --series UID | --series-modality M]
//  [--interpolation nearest|linear] [--format table|json|csv]`: the features of stored structure ID,
// computed (or taken from the cache) by soiqd, printed exactly as the offline command prints them
// (feature_report_output.h). --image names an image series of the structure's study by modality
// ("PT") or uid. The offline `soiq features FILE ...` is features_command.h.

#include "client/soiq_client.h"

namespace soiq::cli {

int run_remote_features_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
