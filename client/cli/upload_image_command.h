#pragma once
// `soiq upload-image IMAGE --patient ID --study UID --series UID --modality PT [--sex M|F|O]
//  [--birth-date YYYYMMDD] [--study-date YYYYMMDD] [--description D]`: stores an image series
//  (.nii, .nii.gz, .nrrd, .mha) on soiqd: a target grid for conversions and the image of intensity
//  features. Prints "series UID: MODALITY, GEOMETRY; new|replaced".

#include "client/soiq_client.h"

namespace soiq::cli {

int run_upload_image_command(int argc, char** argv, const client::ClientOptions& remote);

}  // namespace soiq::cli
