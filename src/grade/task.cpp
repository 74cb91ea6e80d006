#include "grade/task.h"

#include "core/error.h"

namespace pt {

const char* to_string(TaskType type) {
    switch (type) {
        case TaskType::function:
            return "function";
        case TaskType::image:
            return "image";
        case TaskType::performance:
            return "performance";
    }
    return "?";
}

TaskType parse_task_type(const std::string& text, const std::string& where) {
    for (TaskType t : {TaskType::function, TaskType::image, TaskType::performance})
        if (text == to_string(t)) return t;
    throw InputError(where + ": expected \"function\", \"image\" or \"performance\", got \"" +
                     text + "\"");
}

const char* to_string(TaskStatus status) {
    switch (status) {
        case TaskStatus::pass:
            return "pass";
        case TaskStatus::fail:
            return "fail";
        case TaskStatus::not_implemented:
            return "not implemented";
        case TaskStatus::not_submitted:
            return "not submitted";
    }
    return "?";
}

}  // namespace pt
